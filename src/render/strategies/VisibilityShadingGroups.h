#pragma once

// The visibility strategy's shading bins by material. Its shading reads each pixel's material
// from a table of material uniforms (material.wgsl's MATERIAL_TABLE, MaterialResources'
// kTableMaterials per table), so one bind group serves every material of a table that binds the
// same textures and samplers, and untextured materials join the first such group of their
// table (their slots read white without sampling). A bin is a group and whether TANGENT is
// bound: one dispatch each, where a bin per material had been one dispatch per material, each
// with its own bind group for Dawn to track (the CPU frame), and a frame of one bin is shaded
// without binning at all.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <vector>

#include "render/MaterialResources.h"

namespace encore::render {

struct VisibilityPipelines;

struct VisibilityShadingGroup {
    scene::MaterialId representative;  // Whose textures and samplers the group binds.
    std::uint32_t table = 0;           // The material table of its members.
    bool textured = false;             // MATERIAL_TEXTURES.
    bool extensions = false;           // Some member shades the extensions: every slot bound.
    wgpu::BindGroup bindGroup;         // VisibilityPipelines::materialTableLayout's.
};

class VisibilityShadingGroups {
  public:
    // Groups the materials of `materials` and makes each group's bind group.
    void build(const wgpu::Device& device,
               const MaterialResources& materials,
               const VisibilityPipelines& pipelines);

    // Indexed by a primitive record's bin (material * 2 + 1 with TANGENT): its shading bin
    // (group * 2 + the same bit). Never empty.
    const std::vector<std::uint32_t>& shadingBins() const { return mShadingBins; }
    const VisibilityShadingGroup& groupOf(std::uint32_t shadingBin) const {
        return mGroups[shadingBin / 2];
    }
    std::size_t groupCount() const { return mGroups.size(); }

  private:
    std::vector<VisibilityShadingGroup> mGroups;
    std::vector<std::uint32_t> mShadingBins;
};

}  // namespace encore::render
