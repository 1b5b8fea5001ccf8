#pragma once

// What a Renderer is created with (RendererOptions) and the option groups it changes later:
// the target, tone mapping, lighting, the environment's build, culling and animation.
// Free of GPU objects: a caller that only fills options needs no WebGPU state.

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>

#include "encore/render/RenderTarget.h"

namespace encore::image {
class HdrImage;
}

namespace encore::render {

class Environment;

enum class ToneMapping : std::uint32_t {
    None,        // Linear, clamped at 1.
    PbrNeutral,  // Khronos PBR Neutral (the default, as the Khronos Sample Renderer).
    AcesHill,    // ACES filmic, Stephen Hill's fit.
};

enum class BackgroundKind : std::uint32_t {
    Color,        // An opaque colour behind the scene.
    Transparent,  // Alpha 0 where nothing is drawn; colours are straight (not premultiplied).
    Environment,  // The environment map, drawn by EnvironmentBackground and tone mapped.
};

struct ToneMappingOptions {
    ToneMapping toneMapping = ToneMapping::PbrNeutral;
    float exposure = 1.0f;  // Multiplies linear colour before tone mapping.
    BackgroundKind background = BackgroundKind::Color;
    // Linear RGB of BackgroundKind::Color; the default is a neutral dark grey.
    glm::vec3 backgroundColor{0.05f, 0.05f, 0.06f};

    bool operator==(const ToneMappingOptions&) const = default;
};

struct CullingOptions {
    // Two-phase occlusion culling: draw what was visible last frame, build a depth pyramid from
    // it, then draw whatever else the pyramid does not hide. Only for frames of one view (a
    // multi-view frame culls against the frustum only).
    bool occlusion = true;
    // Draw each instance at the coarsest level of detail whose simplification error, projected
    // on the screen, stays under `lodErrorPixels` (level 0, the mesh as loaded, when off).
    bool levelsOfDetail = true;
    float lodErrorPixels = 1.0f;
    // The visibility strategy: triangles whose screen bounds span at most computeRasterPixels
    // each way are rasterised in compute by one thread (at most 64), those up to
    // workgroupRasterPixels by a workgroup in 8x8 tiles (at most 8192), larger ones by the
    // hardware, as do triangles crossing the near or far plane. 6 measured fastest on the H100
    // (docs/visibility-performance.md).
    float computeRasterPixels = 6.0f;
    float workgroupRasterPixels = 8192.0f;
    // The visibility strategy: each cluster (meshlet) of a drawn item is culled on its own
    // against the frustum, by its cone of normals (all its triangles facing away) and, in the
    // second occlusion phase, against the depth pyramid. Off: every triangle of a listed item is
    // rasterised (the same picture; for comparisons).
    bool clusterCulling = true;

    bool operator==(const CullingOptions&) const = default;
};

// What the mesh shader outputs: the shaded colour, or one input of the shading (a debug view;
// tone mapping "none" then shows the value itself).
enum class DebugChannel : std::uint32_t {
    Shaded,
    BaseColor,
    Normal,  // Shading normal, world space, mapped to 0..1.
    Metallic,
    Roughness,
    Occlusion,
    Emissive,
    Depth,     // Distance in front of the camera along its axis (view-space -z), in world units.
    Material,  // glTF's packing: R occlusion, G roughness, B metallic.
    // Segmentation ids, 1 + the index of the drawn node, mesh or material in SceneData (0:
    // nothing drawn), split as R = id % 256, G = id / 256 so that half floats hold them exactly.
    SegmentNode,
    SegmentMesh,
    SegmentMaterial,
    // The triangle's own normal (from the derivatives of its position, facing the viewer), world
    // space, mapped to 0..1: no vertex normals' smoothing, no normal map.
    GeometricNormal,
    Position,  // The surface's world-space position itself, in world units (not mapped).
};

struct LightingParameters {
    float environmentIntensity = 1.0f;
    float environmentRotationRadians = 0.0f;  // About +Y, counter-clockwise seen from above.
    bool imageBasedLighting = true;
    bool punctualLights = true;  // The file's KHR_lights_punctual lights.
    DebugChannel debugChannel = DebugChannel::Shaded;

    bool operator==(const LightingParameters&) const = default;
};

struct EnvironmentOptions {
    std::uint32_t specularSize = 256;  // Level 0 of the specular cube, per face.
    std::uint32_t specularLevels = 5;  // Roughness 0, 0.25, 0.5, 0.75, 1; at most 8.
    std::uint32_t irradianceSize = 32;
    std::uint32_t lutSize = 128;
    // Samples per texel. Each sample reads the source mip that matches its footprint (filtered
    // importance sampling), so these few give smooth maps; the defaults build in about a second
    // on lavapipe.
    std::uint32_t specularSamples = 256;    // GGX importance samples.
    std::uint32_t irradianceSamples = 512;  // Cosine-weighted samples.

    bool operator==(const EnvironmentOptions&) const = default;
};

// Where animation is evaluated.
enum class AnimationEvaluation : std::uint8_t {
    Cpu,  // scene::AnimationPlayer; changed transforms, joints and weights written by the CPU.
    Gpu,  // GpuAnimation: compute passes over keyframes uploaded once.
};

std::string_view animationEvaluationName(AnimationEvaluation evaluation);
std::optional<AnimationEvaluation> animationEvaluationFromName(std::string_view name);

// Pass images drawn in the colour frame's own render pass (encore batch's passes: normal,
// albedo, material, depth and segmentation, docs/batch.md#passes), and what the segmentation
// ids count.
enum class PassTargets : std::uint8_t { None, SegmentByNode, SegmentByMesh, SegmentByMaterial };
// The images of a frame drawn with pass targets (Renderer::passTexture).
enum class PassImage { Normal, Albedo, Material, DepthAndId };

struct RendererOptions {
    RenderTargetOptions target;
    ToneMappingOptions toneMapping;
    LightingParameters lighting;
    // The image-based light; several renderers may share one. Null: the renderer builds one
    // from `environmentImage`, or from the default studio (image::makeStudioEnvironment),
    // with `environmentOptions`.
    std::shared_ptr<Environment> environment;
    std::shared_ptr<const image::HdrImage> environmentImage;
    EnvironmentOptions environmentOptions;
    // Where animation is evaluated (setAnimationEvaluation changes it later).
    AnimationEvaluation animation = AnimationEvaluation::Cpu;
    // Keep the render pipelines of the materials-based and instancing strategies (and the
    // visibility strategy's pipelines and target-sized buffers) from one prepare() to the
    // next: a renderer that prepares many scenes in turn (encore batch) creates
    // each distinct pipeline once, which matters where creating one compiles shaders for
    // hundreds of milliseconds (lavapipe). Off by default, so that each prepare's
    // RenderSetup::pipelinesCreated counts what that strategy needs.
    bool keepPipelines = false;
    // Whether prepare() waits for the GPU to finish everything submitted before it frees the
    // previous scene, so that peak memory stays one scene's worth. Off, the caller makes sure the
    // GPU is done with this renderer's previous scene (encore batch reads its views back first),
    // and prepare() never blocks on work that other renderers of the device submitted.
    bool prepareWaitsForIdle = true;
    // Occlusion culling and levels of detail of the GPU-culling strategies.
    CullingOptions culling;
    // Draws four more colour targets in every scene pass (passTexture): the normal, albedo,
    // material and depth + segmentation id images, each as the matching debug channel's frame
    // would draw it. Needs an HDR target, a strategy that draws glTF materials in its mesh
    // shader (prepare() fails otherwise) and a device with maxColorAttachmentBytesPerSample of
    // at least 40 (create() fails otherwise). None: the frames are drawn as they always were.
    PassTargets passTargets = PassTargets::None;

    // Equal options build equal renderers. The environment and its image compare as pointers:
    // the same shared object, not equal contents.
    bool operator==(const RendererOptions&) const = default;
};

}  // namespace encore::render
