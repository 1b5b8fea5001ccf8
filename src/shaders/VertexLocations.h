#pragma once

#include <cstdint>

namespace encore::shaders {

// Shader locations of the vertex attributes, shared by the C++ pipeline layouts and mesh.wgsl
// (tests/unit/shaders checks that the WGSL declares the same numbers).
inline constexpr std::uint32_t kPositionLocation = 0;
inline constexpr std::uint32_t kNormalLocation = 1;
inline constexpr std::uint32_t kTexcoord0Location = 2;
inline constexpr std::uint32_t kColor0Location = 3;
inline constexpr std::uint32_t kTangentLocation = 4;
inline constexpr std::uint32_t kTexcoord1Location = 5;
// Skinning (mesh.wgsl's SKINNED; the second set with SKINNED_8).
inline constexpr std::uint32_t kJoints0Location = 6;
inline constexpr std::uint32_t kWeights0Location = 7;
inline constexpr std::uint32_t kJoints1Location = 8;
inline constexpr std::uint32_t kWeights1Location = 9;

}  // namespace encore::shaders
