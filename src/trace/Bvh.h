#pragma once

// A bounding volume hierarchy in the layout the GPU traverses (trace_bvh.wgsl): nodes of 32
// bytes in one array, the two children of an interior node side by side, so that a node names
// them with one index and a leaf its items with a range.
//
// Built with Embree's generic builder (rtcBuildBVH: binned surface area heuristic over the
// items' boxes), which gives the tree; Encore keeps only the flattened copy.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "encore/core/Result.h"
#include "encore/scene/SceneData.h"

namespace encore::trace {

struct BvhNode {
    glm::vec3 min{0.0f};
    // Interior: the first child's index (the second is first + 1). Leaf: the first of its
    // `count` items in Bvh::items.
    std::uint32_t first = 0;
    glm::vec3 max{0.0f};
    std::uint32_t count = 0;  // 0 for an interior node.

    bool leaf() const { return count != 0; }
};
static_assert(sizeof(BvhNode) == 32, "trace_bvh.wgsl reads 32-byte nodes");

struct Bvh {
    std::vector<BvhNode> nodes;        // nodes[0] is the root; empty when no item has a box.
    std::vector<std::uint32_t> items;  // The items' indices in leaf order; leaves index this.
};

struct BvhBuildOptions {
    std::uint32_t maxLeafSize = 4;
    // The heuristic's costs of visiting a node and of intersecting an item.
    float traversalCost = 1.0f;
    float intersectionCost = 1.0f;
};

// Owns an Embree device; builds are independent of each other and may run on several threads.
class BvhBuilder {
  public:
    static Result<BvhBuilder> create();

    // A hierarchy over the items' boxes. Empty boxes (an item whose points were all NaN or
    // infinite) are left out: nothing can hit them.
    Result<Bvh> build(std::span<const scene::Bounds> items,
                      const BvhBuildOptions& options = {}) const;

  private:
    struct Device;
    explicit BvhBuilder(std::shared_ptr<Device> device) : mDevice(std::move(device)) {}
    std::shared_ptr<Device> mDevice;
};

}  // namespace encore::trace
