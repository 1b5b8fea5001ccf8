#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "batch/OptionEntries.h"
#include "batch/OptionNames.h"
#include "batch/OptionValues.h"
#include "batch/PoseFile.h"

namespace encore::batch::optiontable {

namespace {

// A list of numbers (--azimuths 0,90,180).
Entry numberList(std::string name,
                 std::string help,
                 std::function<void(BatchOptions&, std::vector<float>)> set) {
    return text(std::move(name), OptionForm::NumberList, "A,B,...", std::move(help),
                [set](BatchOptions& options, std::string_view value,
                      std::string_view shown) -> Result<void> {
                    ENCORE_TRY_ASSIGN(std::vector<float> values,
                                      parseNumberList(value, shown, kMaxViews));
                    set(options, std::move(values));
                    return Result<void>{};
                });
}

// Where the views look from, as the rig draws them.
void addDirectionOptions(std::vector<Entry>& entries) {
    entries.push_back(
        wholeNumber("views", "N", "12", "Views per model on an orbit", 1, kMaxViews,
                    [](BatchOptions& o, std::uint64_t n) { o.views.views = std::uint32_t(n); }));
    entries.push_back(
        wholeNumber("random-views", "N", "",
                    "Views per model drawn uniformly on the sphere instead of the "
                    "orbit",
                    1, kMaxViews,
                    [](BatchOptions& o, std::uint64_t n) {
                        o.views.views = std::uint32_t(n);
                        o.views.distribution = CameraDistribution::Sphere;
                    })
            .excluding({"camera-distribution", "elevation", "azimuths", "elevations"}));
    entries.push_back(
        named<CameraDistribution>(
            "camera-distribution", "orbit",
            "Where the views look from: orbit (evenly around, --elevation high), "
            "sphere or upper-hemisphere (drawn uniformly, per model, from --seed), hammersley "
            "(TRELLIS's Hammersley points, turned per model from --seed) or fibonacci (the "
            "golden-angle spiral)",
            cameraDistributionNames(),
            [](BatchOptions& o, CameraDistribution d) { o.views.distribution = d; })
            .excluding({"random-views", "azimuths", "elevations"}));
    entries.push_back(wholeNumber(
        "seed", "N", "0",
        "Seeds everything drawn at random (directions, jitter, ranges, environments), with each "
        "model's name: the same pictures for the same seed",
        0, kAll, [](BatchOptions& o, std::uint64_t n) { o.views.seed = n; }));
    entries.push_back(range("elevation", "DEG|MIN:MAX", "30",
                            "Orbit height above the horizon in degrees, or MIN:MAX: drawn per "
                            "view",
                            [](BatchOptions& o, ValueRange r) { o.views.elevationDegrees = r; })
                          .excluding({"random-views", "elevations"}));
    entries.push_back(numberList("azimuths",
                                 "The views' azimuths in degrees (0: the model's front, +Z; 90: "
                                 "its +X side), one view each, replacing --views and "
                                 "--camera-distribution",
                                 [](BatchOptions& o, std::vector<float> values) {
                                     o.views.azimuthsDegrees = std::move(values);
                                 })
                          .excluding({"random-views", "camera-distribution"}));
    entries.push_back(numberList("elevations",
                                 "The views' elevations in degrees, one per azimuth or one for "
                                 "all (alone: spread evenly in azimuth)",
                                 [](BatchOptions& o, std::vector<float> values) {
                                     o.views.elevationsDegrees = std::move(values);
                                 })
                          .excluding({"random-views", "camera-distribution", "elevation"}));
    entries.push_back(number("camera-jitter", "DEG", "",
                             "Move each view's direction by up to this many degrees in azimuth "
                             "and elevation (drawn from --seed)",
                             0.0f, 180.0f,
                             [](BatchOptions& o, float v) { o.views.jitterDegrees = v; }));
}

// How far the cameras stand and what they project.
void addLensOptions(std::vector<Entry>& entries) {
    entries.push_back(range("distance", "D|MIN:MAX", "1.5",
                            "Camera distance from the centre (unit-box units unless "
                            "--no-normalize), or MIN:MAX: drawn per view",
                            [](BatchOptions& o, ValueRange r) { o.views.distance = r; })
                          .excluding({"distances"}));
    entries.push_back(numberList("distances",
                                 "Each view's distance from the centre, one per view or one for "
                                 "all",
                                 [](BatchOptions& o, std::vector<float> values) {
                                     o.views.distances = std::move(values);
                                 })
                          .excluding({"distance"}));
    entries.push_back(flag("distance-relative-to-fov",
                           "Count the distance in half-heights of the view at the centre, as "
                           "MVDream does: the camera stands at distance / tan(fov / 2), so the "
                           "model keeps its size in the picture whatever the field of view",
                           [](BatchOptions& o, bool on) { o.views.distanceRelativeToFov = on; }));
    entries.push_back(
        range("fov", "DEG|MIN:MAX", "",
              "Horizontal field of view in degrees, or MIN:MAX: drawn per view "
              "(default: a 35 mm lens on a 32 mm sensor)",
              [](BatchOptions& o, ValueRange r) { o.views.horizontalFovDegrees = r; }));
    entries.push_back(named<Projection>(
        "projection", "perspective",
        "perspective (a pinhole of --fov) or orthographic (parallel rays spanning --ortho-scale); "
        "recorded in transforms.json",
        projectionNames(), [](BatchOptions& o, Projection p) { o.views.projection = p; }));
    entries.push_back(number("ortho-scale", "UNITS", "1.75",
                             "With --projection orthographic: what the view spans across the "
                             "image's larger side, in unit-box units (Blender's ortho_scale); "
                             "1.75 holds the unit box from any direction",
                             0.0f, kNoLimit,
                             [](BatchOptions& o, float v) { o.views.orthoScale = v; })
                          .needing({"projection"}));
    entries.push_back(flag("no-normalize",
                           "Keep the model's size and position (default: scale into a unit box "
                           "centred at the origin)",
                           [](BatchOptions& o, bool on) { o.views.normalize = !on; })
                          .keyword("normalize", /*negated=*/true));
}

// The axes written cameras are in, and cameras given (read in those axes, so after them).
void addPoseOptions(std::vector<Entry>& entries) {
    entries.push_back(named<CameraConvention>(
        "camera-convention", "",
        "The axes of every written camera (transforms.json, .npy, camera files) and of --poses "
        "files without their own: opengl (NeRF's), opencv or blender (+Z up world); recorded in "
        "transforms.json and metadata.json. Default: transforms.json in opengl, .npy in "
        "blender, camera files in opencv",
        cameraConventionNames(),
        [](BatchOptions& o, CameraConvention c) { o.cameraConvention = c; }));
    entries.push_back(
        text("poses", OptionForm::Text, "FILE",
             "Render exactly these cameras, in the unit box: a transforms.json (as encore "
             "writes it), a .npy stack of 3x4 or 4x4 matrices, or a JSON list (docs/batch.md, "
             "Poses)",
             [](BatchOptions& o, std::string_view value, std::string_view shown) -> Result<void> {
                 ENCORE_TRY_ASSIGN(o.views.poses, readPoseFile(std::string(value), shown,
                                                               o.cameraConvention, o.views));
                 o.views.posesFile = std::string(value);
                 return Result<void>{};
             })
            .excluding({"views", "random-views", "camera-distribution", "elevation", "azimuths",
                        "elevations", "distance", "distances", "camera-jitter",
                        "distance-relative-to-fov"}));
}

}  // namespace

void addCameraOptions(std::vector<Entry>& entries) {
    addDirectionOptions(entries);
    addLensOptions(entries);
    addPoseOptions(entries);
}

}  // namespace encore::batch::optiontable
