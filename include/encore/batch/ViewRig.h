#pragma once

// The cameras of a batch: where each view looks from, in the frame the outputs describe.
//
// Views are camera-to-world matrices in OpenGL's camera axes (the camera looks along its -Z
// axis, +Y up, +X right), the convention of NeRF's transforms.json. The world is the model's
// glTF frame (+Y up), normalised by default into a unit box: the model is scaled so that its
// largest side is 1 and centred at the origin, as the Objaverse rendering scripts do. Every
// camera the rig places looks at the origin; cameras given (`poses`) look where they were
// written to. Written cameras may be expressed in other axes (CameraConvention), and read back
// from them.
//
// The defaults follow those scripts: 12 views on a circle 30 degrees above the horizon, 1.5
// units from the centre, with a 35 mm lens on a 32 mm wide sensor (a horizontal field of view
// of 2 atan(16 / 35), about 49.13 degrees).
//
// What a rig draws at random (directions on the sphere, a jitter, distances and fields of view
// from ranges) comes from its seed and the model's name (ModelSeed.h): each model has views of
// its own, the same ones whatever order the models are rendered in.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "encore/render/Camera.h"
#include "encore/scene/SceneData.h"

namespace encore::batch {

// A value that a batch may vary from view to view or model to model: fixed (min == max), or
// drawn uniformly between min and max from the batch's seed (`--distance 1.5:2.2`).
struct ValueRange {
    float min = 0.0f;
    float max = 0.0f;

    constexpr ValueRange() = default;
    // A fixed value: options that took one number before still take it.
    constexpr ValueRange(float value) : min(value), max(value) {}  // NOLINT(google-explicit-*)
    constexpr ValueRange(float low, float high) : min(low), max(high) {}

    bool fixed() const { return min == max; }
    // min + unit (max - min), for unit in [0, 1): exactly min when fixed.
    float at(double unit) const {
        return fixed() ? min : float(double(min) + unit * (double(max) - double(min)));
    }

    bool operator==(const ValueRange&) const = default;
};

inline constexpr float kDefaultHorizontalFovDegrees = 49.134343f;  // 2 atan(16 / 35)

// Where the views' directions come from. Azimuths are measured in the glTF frame from +Z (the
// side a glTF model faces) towards +X; elevations above the horizontal plane, towards +Y.
enum class CameraDistribution {
    // View i at azimuth 360 i / views degrees (view 0 on +Z, then towards +X), elevationDegrees
    // above the horizontal plane.
    Orbit,
    Sphere,           // Uniform on the sphere, drawn from the seed.
    UpperHemisphere,  // Uniform on the half above the horizontal plane (+Y), from the seed.
    // The Hammersley point set on the sphere as TRELLIS's dataset_toolkits/render.py places its
    // views (sphere_hammersley_sequence): view i at height 2 (i + u) / views - 1 and azimuth
    // 360 (radicalInverse2(i) + v) degrees + 90 (TRELLIS's yaw is measured from Blender's +X,
    // which is 90 degrees from glTF's +Z), with the offsets u and v in [0, 1) drawn per model from
    // the seed. Low-discrepancy: evenly covered at any count.
    Hammersley,
    // The Fibonacci (golden-angle) spiral: view i at height 1 - (2 i + 1) / views and azimuth
    // i times the golden angle (180 (3 - sqrt 5) degrees). Evenly covered, nothing drawn.
    Fibonacci,
};

// What the renders project with.
enum class Projection {
    Perspective,  // A pinhole camera of horizontalFovDegrees.
    // Parallel rays: the view spans orthoScale units of the normalised world across the larger
    // side of the image (Blender's ortho_scale), orthoScale times height / width across a
    // narrower height.
    Orthographic,
};

// One view: where the camera is and how wide it sees.
struct ViewCamera {
    glm::mat4 cameraToWorld{1.0f};
    float horizontalFovRadians = 0.0f;  // Perspective.
    Projection projection = Projection::Perspective;
    float orthoScale = 0.0f;  // Orthographic: Projection's span, in normalised units.

    bool operator==(const ViewCamera&) const = default;
};

// The axes a written camera is expressed in (--camera-convention). Encore's own are OpenGL's.
enum class CameraConvention {
    // The glTF world (+Y up); the camera looks along its -Z axis, +Y up, +X right (NeRF's
    // transforms.json, nerfstudio, instant-ngp).
    OpenGl,
    // The glTF world; the camera looks along +Z, +Y down, +X right (OpenCV, COLMAP, G-Objaverse's
    // camera files).
    OpenCv,
    // Blender's world (+Z up: glTF's (x, y, z) is Blender's (x, -z, y), as its glTF importer
    // turns it) and Blender's camera axes, which are OpenGL's (the Objaverse scripts' matrices).
    Blender,
};

// The view's span across the larger side of the image (--ortho-scale) unless told otherwise:
// the unit box's diagonal (1.73) fits from any direction.
inline constexpr float kDefaultOrthoScale = 1.75f;

struct ViewRigOptions {
    std::uint32_t views = 12;
    CameraDistribution distribution = CameraDistribution::Orbit;
    // Of the orbit: fixed, or drawn per view from the range.
    ValueRange elevationDegrees = 30.0f;
    // Fixed directions (--azimuths, --elevations), which replace `distribution`: view i at
    // azimuthsDegrees[i] and elevationsDegrees[i]; azimuths alone take elevationDegrees,
    // elevations alone are spread evenly in azimuth (360 i / views). Each view's distance
    // (--distances) the same way, replacing `distance`. A list of one value applies to every
    // view; lists of several values all have one length, which is the number of views (replacing
    // `views`; validateBatchOptions checks it).
    std::vector<float> azimuthsDegrees;
    std::vector<float> elevationsDegrees;
    std::vector<float> distances;
    // Seeds every draw: directions, jitter, distances and fields of view (and, in a batch, the
    // lighting of BatchLighting.h). The same seed gives the same views on every machine.
    std::uint64_t seed = 0;
    // Each view's distance from the origin, in (normalised) world units, and its horizontal
    // field of view: fixed, or drawn per view from the range.
    ValueRange distance = 1.5f;
    ValueRange horizontalFovDegrees = kDefaultHorizontalFovDegrees;
    // Moves each view's direction by up to this many degrees in azimuth and in elevation
    // (uniformly, from the seed; elevations stay within the poles). 0: none.
    float jitterDegrees = 0.0f;
    // The distance counts in half-heights of the view at the origin, as MVDream's renders draw
    // theirs (threestudio's relative_radius): the camera stands at distance / tan(vertical
    // field of view / 2), so the object keeps its size in the picture whatever the field of view.
    bool distanceRelativeToFov = false;
    bool normalize = true;  // False: the model as it is, cameras around the world origin.
    Projection projection = Projection::Perspective;
    float orthoScale = kDefaultOrthoScale;
    // Cameras given as they are (--poses, PoseFile.h): when not empty, the views are these, and
    // every option above that places or shapes a camera is ignored.
    std::vector<ViewCamera> poses;
    std::string posesFile;  // Where they came from, as given (metadata.json records it).
};

// The number of views the options make (`views`, the lists' length, or the poses').
std::uint32_t viewCount(const ViewRigOptions& options);

// The farthest a camera may stand from the origin (the largest distance the options give), in
// the rig's units: what 16-bit depth is scaled by (ViewStrips.h, depthScale).
float farthestDistance(const ViewRigOptions& options);

// The camera-to-world matrix of a camera at `eye` looking at `target` with +Y up (-Z up when
// looking straight up or down, as render::Camera::lookAt does).
glm::mat4 lookAtCameraToWorld(const glm::vec3& eye, const glm::vec3& target);

// The views of the model named `modelName` (BatchInput::name), as the options ask; with an
// empty name, the draws come from the seed alone.
std::vector<ViewCamera> viewCameras(const ViewRigOptions& options, std::string_view modelName = {});

// Their camera-to-world matrices.
std::vector<glm::mat4> viewMatrices(const ViewRigOptions& options, std::string_view modelName = {});

// The transform from the model's world into the normalised world: uniform scale and
// translation putting `bounds` into the unit box centred at the origin (identity for empty or
// flat-to-a-point bounds, or without normalisation).
glm::mat4 normalization(const scene::Bounds& bounds, bool normalize);

// The vertical field of view for a horizontal one at `aspect` (width / height), in radians.
float verticalFov(float horizontalFovRadians, float aspect);

// An orthographic view's half-width and half-height (glTF's xmag and ymag) for `orthoScale`
// across the larger side of an image of `aspect` (width / height).
glm::vec2 orthographicHalfExtent(float orthoScale, float aspect);

// The render camera for one view: `cameraToWorld` (in the normalised world) taken back into
// the model's world through the inverse of `normalization` (a uniform scale and translation),
// so the picture is the one of the normalised model. Perspective with an infinite far plane and
// a near plane at 1/100 of the distance to the origin.
render::Camera renderCamera(const glm::mat4& cameraToWorld,
                            const glm::mat4& normalization,
                            float horizontalFovRadians,
                            float aspect);
// The same for any view: perspective as above; orthographic with its span (orthoScale in the
// normalised world) and clip distances from 1/100 of the camera's distance to the origin out to
// 100 times it.
render::Camera renderCamera(const ViewCamera& view, const glm::mat4& normalization, float aspect);

}  // namespace encore::batch
