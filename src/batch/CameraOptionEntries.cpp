#include <cstdint>
#include <string>
#include <vector>

#include "batch/OptionEntries.h"
#include "batch/OptionNames.h"

namespace encore::batch::optiontable {

// Where the views look from, what they see and how far they stand.
void addCameraOptions(std::vector<Entry>& entries) {
    entries.push_back(
        wholeNumber("views", "N", "12", "Views per model on an orbit", 1, kMaxViews,
                    [](BatchOptions& o, std::uint64_t n) { o.views.views = std::uint32_t(n); }));
    entries.push_back(wholeNumber("random-views", "N", "",
                                  "Views per model drawn uniformly on the sphere instead of the "
                                  "orbit",
                                  1, kMaxViews,
                                  [](BatchOptions& o, std::uint64_t n) {
                                      o.views.views = std::uint32_t(n);
                                      o.views.distribution = CameraDistribution::Sphere;
                                  })
                          .excluding({"camera-distribution", "elevation"}));
    entries.push_back(named<CameraDistribution>(
                          "camera-distribution", "orbit",
                          "Where the views look from: orbit (evenly around, --elevation high), "
                          "sphere or upper-hemisphere (drawn uniformly, per model, from --seed)",
                          cameraDistributionNames(),
                          [](BatchOptions& o, CameraDistribution d) { o.views.distribution = d; })
                          .excluding({"random-views"}));
    entries.push_back(wholeNumber(
        "seed", "N", "0",
        "Seeds everything drawn at random (directions, jitter, ranges, environments), with each "
        "model's name: the same pictures for the same seed",
        0, kAll, [](BatchOptions& o, std::uint64_t n) { o.views.seed = n; }));
    entries.push_back(number("elevation", "DEG", "30", "Orbit height above the horizon (degrees)",
                             -90.0f, 90.0f,
                             [](BatchOptions& o, float v) { o.views.elevationDegrees = v; })
                          .excluding({"random-views"}));
    entries.push_back(range("distance", "D|MIN:MAX", "1.5",
                            "Camera distance from the centre (unit-box units unless "
                            "--no-normalize), or MIN:MAX: drawn per view",
                            [](BatchOptions& o, ValueRange r) { o.views.distance = r; }));
    entries.push_back(
        range("fov", "DEG|MIN:MAX", "",
              "Horizontal field of view in degrees, or MIN:MAX: drawn per view "
              "(default: a 35 mm lens on a 32 mm sensor)",
              [](BatchOptions& o, ValueRange r) { o.views.horizontalFovDegrees = r; }));
    entries.push_back(number("camera-jitter", "DEG", "",
                             "Move each view's direction by up to this many degrees in azimuth "
                             "and elevation (drawn from --seed)",
                             0.0f, 180.0f,
                             [](BatchOptions& o, float v) { o.views.jitterDegrees = v; }));
    entries.push_back(flag("no-normalize",
                           "Keep the model's size and position (default: scale into a unit box "
                           "centred at the origin)",
                           [](BatchOptions& o, bool on) { o.views.normalize = !on; })
                          .keyword("normalize", /*negated=*/true));
}

}  // namespace encore::batch::optiontable
