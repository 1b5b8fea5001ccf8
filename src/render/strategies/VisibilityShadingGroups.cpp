#include "render/strategies/VisibilityShadingGroups.h"

#include <algorithm>

#include "render/strategies/VisibilityPipelines.h"

namespace encore::render {

void VisibilityShadingGroups::build(const wgpu::Device& device,
                                    const MaterialResources& materials,
                                    const VisibilityPipelines& pipelines) {
    mGroups.clear();
    const std::size_t count = materials.materialCount();
    std::vector<std::uint32_t> groupOfMaterial(count, 0);
    std::vector<std::size_t> untextured;
    for (std::size_t first = 0; first < count; first += MaterialResources::kTableMaterials) {
        const std::size_t end = std::min(count, first + MaterialResources::kTableMaterials);
        const auto table = std::uint32_t(first / MaterialResources::kTableMaterials);
        const std::size_t tableGroups = mGroups.size();
        untextured.clear();
        for (std::size_t index = first; index < end; ++index) {
            const scene::MaterialId material(index);
            if (!materials.textured(material)) {
                untextured.push_back(index);
                continue;
            }
            std::size_t group = tableGroups;
            while (group < mGroups.size() &&
                   !materials.sameTextures(mGroups[group].representative, material)) {
                ++group;
            }
            if (group == mGroups.size()) {
                mGroups.push_back({material, table, true, false, {}});
            }
            mGroups[group].extensions =
                mGroups[group].extensions || materials.shadesExtensions(material);
            groupOfMaterial[index] = std::uint32_t(group);
        }
        // Untextured materials read white in every slot: any textured group of the table takes
        // them (the first), else one of their own.
        if (!untextured.empty() && tableGroups == mGroups.size()) {
            mGroups.push_back({scene::MaterialId(untextured.front()), table, false, false, {}});
        }
        for (std::size_t index : untextured) {
            mGroups[tableGroups].extensions = mGroups[tableGroups].extensions ||
                                              materials.shadesExtensions(scene::MaterialId(index));
            groupOfMaterial[index] = std::uint32_t(tableGroups);
        }
    }
    for (VisibilityShadingGroup& group : mGroups) {
        group.bindGroup = materials.createTableBindGroup(
            device, pipelines.materialTableLayout(group.textured, group.extensions),
            group.representative, group.table, group.textured, group.extensions,
            "visibility material table");
    }
    mShadingBins.assign(std::max<std::size_t>(count, 1) * 2, 0);
    for (std::size_t index = 0; index < count; ++index) {
        mShadingBins[index * 2] = groupOfMaterial[index] * 2;
        mShadingBins[index * 2 + 1] = groupOfMaterial[index] * 2 + 1;
    }
}

}  // namespace encore::render
