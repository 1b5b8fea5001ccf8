#pragma once

// The visibility strategy's shading bins (visibility_shade.wgsl): a dispatch per bin, with the
// bind group and pipeline of the bin's first material. Materials that bind the same textures
// and samplers (MaterialResources::sharedBindingLeaders) share bins, up to kBinMaterials each,
// and so do untextured materials with the first textured ones of their variant (their uniform
// skips every texture), so that a frame of many materials is not a dispatch per material: on
// the H100 every bin dispatch waits for the one before (WebGPU orders dispatches that write one
// buffer), at least the latency of one pixel's shading each. The shading reads each pixel's
// material from its bin's block of a uniform table (a copy of the materials' uniforms,
// kSlotBytes each), at the slot its primitive record names.
//
// A bin is leader * 2 + 1 with a bound TANGENT (the variant), `leader` the first material of
// its block; a record's bin word is the bin in its low kSlotShift bits and the slot above.

#include <cstdint>
#include <vector>

namespace encore::render {

class MaterialResources;

class MaterialBins {
  public:
    static constexpr std::uint32_t kBinMaterials = 64;  // Slots of a block.
    static constexpr std::uint64_t kSlotBytes = 1024;   // A MaterialUniform, padded.
    // The uniform binding of a block: kBinMaterials slots (WebGPU's 64 KiB default).
    static constexpr std::uint64_t kBlockBytes = kBinMaterials * kSlotBytes;
    // A bin word: the bin in its low 26 bits (scenes of up to 2^25 materials), the slot above.
    static constexpr std::uint32_t kSlotShift = 26;
    static constexpr std::uint32_t kBinMask = (1u << kSlotShift) - 1;

    MaterialBins() = default;
    // Groups the materials by what they bind, in order, kBinMaterials to a block.
    explicit MaterialBins(const MaterialResources& materials);

    // The bin word of a primitive of `material` (with a bound TANGENT or not).
    std::uint32_t binWord(std::uint32_t material, bool tangent) const;
    // The byte offset of the block of bin `bin` in the table: its uniform binding's dynamic
    // offset.
    std::uint32_t blockOffset(std::uint32_t bin) const;
    // Where each material's uniform goes in the table (bytes): its block's slots follow each
    // other.
    std::uint64_t slotOffset(std::uint32_t material) const;
    // The table's size: every block, the last one whole.
    std::uint64_t tableBytes() const;
    std::size_t materialCount() const { return mLeader.size(); }

    bool operator==(const MaterialBins&) const = default;

  private:
    std::vector<std::uint32_t> mLeader;  // Material -> the first material of its block.
    std::vector<std::uint32_t> mSlot;    // Material -> its slot in the block.
    std::vector<std::uint32_t> mBlock;   // Material -> its block's first slot in the table.
};

}  // namespace encore::render
