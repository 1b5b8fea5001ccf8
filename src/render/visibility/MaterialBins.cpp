#include "render/visibility/MaterialBins.h"

#include <algorithm>
#include <cassert>
#include <map>

#include "encore/scene/SceneData.h"
#include "render/MaterialResources.h"

namespace encore::render {

MaterialBins::MaterialBins(const MaterialResources& materials) {
    const std::vector<std::uint32_t> leaders = materials.sharedBindingLeaders();
    const std::uint32_t count = std::uint32_t(leaders.size());
    auto textured = [&](std::uint32_t material) {
        return materials.textured(scene::MaterialId(material));
    };
    auto extensions = [&](std::uint32_t material) {
        return materials.shadesExtensions(scene::MaterialId(material));
    };
    // An untextured material shades with a textured bin's pipeline and bind group too: its
    // uniform says that no slot has a texture of its own, so nothing is sampled (white, as its
    // own variant reads). It joins the first textured class of its variant, if there is one.
    std::map<bool, std::uint32_t> firstTextured;  // shadesExtensions -> that class's leader.
    for (std::uint32_t material = 0; material < count; ++material) {
        if (textured(material)) {
            firstTextured.try_emplace(extensions(material), leaders[material]);
        }
    }
    // Each class's members, textured ones first: a block of untextured ones alone (past the
    // first kBinMaterials) takes the untextured pipeline of its untextured leader.
    std::map<std::uint32_t, std::vector<std::uint32_t>> classes;
    for (const bool texturedFirst : {true, false}) {
        for (std::uint32_t material = 0; material < count; ++material) {
            if (textured(material) != texturedFirst) {
                continue;
            }
            const auto joined = firstTextured.find(extensions(material));
            const std::uint32_t leader =
                texturedFirst || joined == firstTextured.end() ? leaders[material] : joined->second;
            classes[leader].push_back(material);
        }
    }
    mLeader.resize(count);
    mSlot.resize(count);
    mBlock.resize(count);
    // Blocks follow each other, as many slots as they have materials: a slot per material.
    std::uint32_t slots = 0;
    for (const auto& [leader, members] : classes) {
        for (std::size_t first = 0; first < members.size(); first += kBinMaterials) {
            const std::size_t end = std::min<std::size_t>(members.size(), first + kBinMaterials);
            for (std::size_t member = first; member < end; ++member) {
                mLeader[members[member]] = members[first];
                mSlot[members[member]] = std::uint32_t(member - first);
                mBlock[members[member]] = slots;
            }
            slots += std::uint32_t(end - first);
        }
    }
}

std::uint32_t MaterialBins::binWord(std::uint32_t material, bool tangent) const {
    assert(material < mLeader.size());
    return (mLeader[material] * 2 + (tangent ? 1 : 0)) | mSlot[material] << kSlotShift;
}

std::uint32_t MaterialBins::blockOffset(std::uint32_t bin) const {
    assert(bin / 2 < mBlock.size());
    return std::uint32_t(mBlock[bin / 2] * kSlotBytes);
}

std::uint64_t MaterialBins::slotOffset(std::uint32_t material) const {
    assert(material < mBlock.size());
    return (std::uint64_t(mBlock[material]) + mSlot[material]) * kSlotBytes;
}

std::uint64_t MaterialBins::tableBytes() const {
    // A slot per material, and room for a whole block's binding from the last block's start.
    return std::uint64_t(materialCount()) * kSlotBytes + kBlockBytes;
}

}  // namespace encore::render
