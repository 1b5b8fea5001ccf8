#pragma once

// The strategies by name, and the bundling axis: what the command line, reports and the Python
// module choose from. Free of WebGPU, so that parsing a choice needs no GPU headers.

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace encore::render {

enum class StrategyKind {
    // One pipeline per primitive; one uniform buffer + bind group per node; each attribute
    // copied into its own tightly packed vertex buffer and bound to its own slot.
    Naive,
    // Vertex data bound in place: one buffer per bufferView, offsets in setVertexBuffer,
    // interleaved attributes bound once. Still one pipeline per primitive.
    Layouts,
    // Pipelines cached by every pipeline argument; loop pipeline -> primitive -> node.
    PipelineCache,
    // All transforms in one storage buffer; one draw per primitive for all its instances.
    Instancing,
    // glTF materials: base colour factor/texture/sampler, MASK, BLEND (sorted back to front),
    // double-sided culling; loop pipeline -> material -> primitive.
    Materials,
    // The materials frame recorded once into render bundles and replayed with executeBundles;
    // dynamic data changes through buffers.
    Bundles,
    // GPU frustum culling: a compute pass writes indirect instance counts and visible lists;
    // one indirect draw per primitive, recorded directly every frame.
    GpuCulling,
    // GPU culling with the indirect draws recorded once into a render bundle.
    GpuCullingBundles,
    // A visibility buffer: small triangles rasterised in compute (64-bit atomics of depth and
    // triangle id), large ones by the hardware into the same buffer, then shaded per pixel in
    // compute. Needs the AtomicVec2uMinMax feature (docs/visibility.md).
    Visibility,
};

std::string_view strategyName(StrategyKind kind);
std::optional<StrategyKind> strategyFromName(std::string_view name);
std::span<const StrategyKind> allStrategies();

// The bundling axis. Every strategy can draw its frame from render bundles: `materials` and
// `gpu-culling` have their own bundled kinds (`bundles`, `gpu-culling-bundles`, which also keep
// blended geometry sorted); the others, whose recording does not depend on the camera, are
// recorded once into a bundle by a wrapper. bundledKind names the own bundled kind (a bundled
// kind names itself), directKind the direct kind of a bundled one (nullopt for the others).
std::optional<StrategyKind> bundledKind(StrategyKind kind);
std::optional<StrategyKind> directKind(StrategyKind kind);
bool isBundledKind(StrategyKind kind);
// The kinds whose culling pass chooses what to draw (render::CullingOptions applies to them).
bool cullsOnTheGpu(StrategyKind kind);

// A point on both axes: a strategy, drawn directly or recorded once into render bundles.
// Normalised so that equal frames compare equal: a kind with a bundled kind of its own is
// bundled by naming that kind (`materials` bundled is `bundles`, with bundle false).
struct StrategyChoice {
    StrategyKind kind = StrategyKind::Bundles;
    bool bundle = false;

    static StrategyChoice of(StrategyKind kind, bool bundle);
    bool operator==(const StrategyChoice&) const = default;
};

// The choice's name in reports and on the command line: the kind's name, or for a kind recorded
// by the bundling wrapper "<name>+bundle" (`naive+bundle`).
std::string strategyChoiceName(StrategyChoice choice);
// Reads strategyChoiceName's names back; nullopt for anything else.
std::optional<StrategyChoice> strategyChoiceFromName(std::string_view name);
// `choices`, each followed (with `alsoBundled`) by its bundled form, every distinct choice once
// in first-seen order: the bundling axis of `stats --bundle` and `bench --bundle`.
std::vector<StrategyChoice> withBundlingAxis(std::span<const StrategyChoice> choices,
                                             bool alsoBundled);

}  // namespace encore::render
