#pragma once

// Strong index types for cross-references inside SceneData. An id is an index into the
// matching vector of SceneData; distinct types keep a MeshId from being used as a MaterialId.

#include <compare>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>

namespace encore::scene {

template <typename Tag>
struct Id {
    static constexpr std::uint32_t kInvalid = std::numeric_limits<std::uint32_t>::max();

    std::uint32_t value = kInvalid;

    constexpr Id() = default;
    constexpr explicit Id(std::uint32_t index) : value(index) {}
    constexpr explicit Id(std::size_t index) : value(static_cast<std::uint32_t>(index)) {}

    constexpr bool valid() const { return value != kInvalid; }
    constexpr std::size_t index() const { return value; }
    constexpr auto operator<=>(const Id&) const = default;
};

using BufferId = Id<struct BufferTag>;
using BufferViewId = Id<struct BufferViewTag>;
using AccessorId = Id<struct AccessorTag>;
using MeshId = Id<struct MeshTag>;
using MaterialId = Id<struct MaterialTag>;
using TextureId = Id<struct TextureTag>;
using SamplerId = Id<struct SamplerTag>;
using ImageId = Id<struct ImageTag>;
using NodeId = Id<struct NodeTag>;
using LightId = Id<struct LightTag>;
using CameraId = Id<struct CameraTag>;
using SkinId = Id<struct SkinTag>;
using AnimationId = Id<struct AnimationTag>;
using VariantId =
    Id<struct VariantTag>;  // KHR_materials_variants: an index into SceneData::variants.

}  // namespace encore::scene

template <typename Tag>
struct std::hash<encore::scene::Id<Tag>> {
    std::size_t operator()(const encore::scene::Id<Tag>& id) const noexcept {
        return std::hash<std::uint32_t>{}(id.value);
    }
};
