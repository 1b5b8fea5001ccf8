#pragma once

// Generates glTF 2.0 scenes for demos and benchmarks: `meshCount` distinct procedural meshes
// (boxes, spheres, cylinders, cones, tori at varying tessellation), `materialCount` shared
// materials, and `objectCount` nodes instancing them in one of three layouts (SceneLayout). The
// output is a self-contained .glb that any glTF viewer opens, so benchmarks exercise the same
// loading path as real assets. The same options and seed always give the same bytes.

#include <cstdint>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "encore/core/Result.h"

namespace encore::scene {

// Where the generated objects stand. Each layout's geometry is public (latticeLayout,
// cityLayout) so that a camera path (render::CameraPath) can follow its free space.
enum class SceneLayout : std::uint8_t {
    // A square grid in the XZ plane (y = 0), seen from outside (render::Camera::framing).
    Grid,
    // A wide, flat box: objects on every point of a side x layers x side lattice, with aisles
    // between the points that a camera flies along at object height (the fly-through).
    Lattice,
    // Buildings (box meshes scaled to varying footprints and heights) on a street grid, 3 x 3
    // lots per block, and small objects (the other meshes) on the pavements; a camera at street
    // level sees the nearest rows of buildings, which hide the rest.
    City,
};

std::string_view sceneLayoutName(SceneLayout layout);

struct GeneratorOptions {
    SceneLayout layout = SceneLayout::Grid;
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

// The lattice of SceneLayout::Lattice: object i stands at
// origin + spacing * (i % side, i / (side * side), (i / side) % side), filling the bottom layer
// first; about four times wider than high (layers = cbrt(objects / 16)). The generated meshes
// are about a unit wide and scaled by at most 1, so with the default spacing (1.5) a line along
// an aisle of X and an aisle of Y (or of Z and Y) passes every object at more than its reach:
// spacing / sqrt(2) > 1.
struct LatticeLayout {
    std::uint32_t side = 1;    // Points along X and Z.
    std::uint32_t layers = 1;  // Points along Y.
    float spacing = 1.5f;      // Between neighbouring points.
    glm::vec3 origin{0.0f};    // The first point.

    // The coordinate of the aisle between points k and k + 1 along one axis (k may be -1 or
    // `count - 1`: just outside the lattice), relative to the origin's coordinate.
    float aisle(int k) const { return (float(k) + 0.5f) * spacing; }
};
LatticeLayout latticeLayout(const GeneratorOptions& options);

// The street grid of SceneLayout::City, in the XZ plane with the ground at y = 0. Blocks of
// 3 x 3 lots (one building each) stand between streets; object i belongs to block i / 12 (row
// by row along X, `blocksPerSide` per row): its slots 0-8 are the buildings, 9-11 small objects
// on the pavement. Street k (0 to blocksPerSide) runs along Z at x = streetCenter(k) and along
// X at z = streetCenter(k).
struct CityLayout {
    static constexpr std::uint32_t kObjectsPerBlock = 12;
    static constexpr std::uint32_t kLotsPerSide = 3;
    std::uint32_t blocksPerSide = 1;
    float lotSize = 2.0f;
    float streetWidth = 4.0f;
    float maxBuildingHeight = 8.0f;

    float blockSize() const { return float(kLotsPerSide) * lotSize; }
    float pitch() const { return blockSize() + streetWidth; }
    // Centred on the origin: street 0 is the west (and south) edge of the city.
    float streetCenter(int k) const { return (float(k) - 0.5f * float(blocksPerSide)) * pitch(); }
};
CityLayout cityLayout(const GeneratorOptions& options);

// The scene as .glb bytes.
Result<std::vector<std::uint8_t>> generateSceneGlb(const GeneratorOptions& options);

}  // namespace encore::scene
