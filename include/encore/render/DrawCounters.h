#pragma once

#include <cstdint>
#include <string>

namespace encore::render {

// WebGPU calls recorded for one frame (or into one bundle), tallied by RenderEncoder, plus what
// the draws drew. The case study's stats, separated: it summed vertex and index buffer sets.
struct DrawCounters {
    std::uint64_t setPipeline = 0;
    std::uint64_t setBindGroup = 0;
    std::uint64_t setVertexBuffer = 0;
    std::uint64_t setIndexBuffer = 0;
    std::uint64_t draw = 0;
    std::uint64_t drawIndexed = 0;
    std::uint64_t drawIndirect = 0;  // drawIndirect + drawIndexedIndirect.
    std::uint64_t executeBundles = 0;
    std::uint64_t primitives = 0;  // Primitive draws issued (one per draw call).
    std::uint64_t instances = 0;   // Sum of instanceCount over direct draws.
    std::uint64_t triangles = 0;   // Triangles of direct draws (list and strip topologies).

    std::uint64_t drawCalls() const { return draw + drawIndexed + drawIndirect; }
    // Every counted encoder call.
    std::uint64_t apiCalls() const {
        return setPipeline + setBindGroup + setVertexBuffer + setIndexBuffer + drawCalls() +
               executeBundles;
    }
    DrawCounters& operator+=(const DrawCounters& other);
    bool operator==(const DrawCounters&) const = default;
};

}  // namespace encore::render
