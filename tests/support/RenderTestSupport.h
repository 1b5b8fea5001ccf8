#pragma once

// Cameras and projections shared by the pixel tests of tests/gpu.

#include <array>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>

#include "encore/render/Camera.h"
#include "encore/render/Renderer.h"
#include "render/culling/GpuCuller.h"

namespace encore::test {

// A camera on the +Z axis (shifted by `x`) looking down -Z at z = 0, 90 degree field of view:
// at z = 0 the view spans [-3, 3] vertically, so tests can place geometry in known pixels.
inline render::Camera frontCamera(float aspect = 1.0f, float x = 0.0f) {
    return render::Camera::lookAt({x, 0.0f, 3.0f}, {x, 0.0f, 0.0f}, glm::half_pi<float>(), aspect,
                                  0.1f, 10.0f);
}

// The pixel of a `width` x `height` image that a world point projects to.
inline std::pair<std::uint32_t, std::uint32_t> pixelOf(const render::Camera& camera,
                                                       const glm::vec3& point,
                                                       std::uint32_t width,
                                                       std::uint32_t height) {
    const glm::vec4 clip = camera.projection * camera.view * glm::vec4(point, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return {static_cast<std::uint32_t>((ndc.x * 0.5f + 0.5f) * float(width)),
            static_cast<std::uint32_t>((0.5f - ndc.y * 0.5f) * float(height))};
}

// Environment maps small enough to build in well under a second on lavapipe.
render::EnvironmentOptions testEnvironmentOptions();

// The default studio environment at test size, built once per test process and shared by the
// renderers of pixelTestOptions.
std::shared_ptr<render::Environment> testEnvironment();

// Renderer options for exact pixel checks: the shared test environment, no tone mapping (so a
// linear value v encodes to linearToSrgb8(v)), the renderer's neutral background, and the mesh
// shader's output channel (BaseColor: materials strategies write their base colour unlit, which
// tests can predict exactly; Shaded: the full physically based result). GPU culling draws every
// instance at full detail (levels of detail off); occlusion culling stays on.
render::RendererOptions pixelTestOptions(
    std::uint32_t width,
    std::uint32_t height,
    std::uint32_t samples = 1,
    render::DebugChannel channel = render::DebugChannel::BaseColor);

// The render bundles a bundled strategy records at once and executes per frame (of one view):
// gpu-culling-bundles draws its frame in two passes for occlusion culling, one bundle each; the
// others record one.
inline std::uint64_t bundlesPerRecording(render::StrategyKind kind) {
    return kind == render::StrategyKind::GpuCullingBundles ? 2 : 1;
}

// The instance counts GPU culling wrote, per culled draw, level of detail and phase (read back;
// a failed read or a non-zero firstInstance fails the test): counts[draw][level][phase].
using CulledCounts = std::vector<std::vector<std::array<std::uint32_t, 2>>>;
CulledCounts culledCountsByLevel(gpu::Context& context, const render::GpuCuller& culler);

// The same, per culled draw, summed over its levels of detail and both phases.
std::vector<std::uint32_t> culledInstanceCounts(gpu::Context& context,
                                                const render::GpuCuller& culler);

}  // namespace encore::test
