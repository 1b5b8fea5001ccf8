#pragma once

// Generates glTF 2.0 scenes for demos and benchmarks: `meshCount` distinct procedural meshes
// (boxes, spheres, cylinders, cones, tori at varying tessellation), `materialCount` shared
// materials, and `objectCount` nodes instancing them in a grid. The output is a self-contained
// .glb that any glTF viewer opens, so benchmarks exercise the same loading path as real assets.

#include <cstdint>
#include <vector>

#include "encore/core/Result.h"

namespace encore::scene {

struct GeneratorOptions {
    std::uint32_t objectCount = 1000;
    std::uint32_t meshCount = 8;
    std::uint32_t materialCount = 4;
    std::uint32_t seed = 1;
    // Distance between neighbouring objects, in object radii (>= 2 keeps objects apart).
    float spacing = 3.0f;
    // Segments around the round shapes of the first meshes (later meshes add more). Small
    // values keep triangle counts low when a CPU rasteriser draws 100,000 objects.
    std::uint32_t tessellation = 8;
    // Every other material (odd indices) also samples two textures: a base colour checker that
    // its factor tints and a metallic-roughness map (metal and dielectric bands, a roughness
    // ramp). The others stay texture-less, so a scene draws both material layouts.
    bool textures = false;
};

// Limits that keep a typo from generating gigabytes.
inline constexpr std::uint32_t kMaxGeneratedObjects = 1'000'000;
inline constexpr std::uint32_t kMaxGeneratedMeshes = 4096;
inline constexpr std::uint32_t kMaxGeneratedMaterials = 4096;

// The scene as .glb bytes.
Result<std::vector<std::uint8_t>> generateSceneGlb(const GeneratorOptions& options);

}  // namespace encore::scene
