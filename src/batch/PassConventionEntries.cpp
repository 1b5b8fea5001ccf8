// The options that say what a pass's values mean (docs/batch.md#conventions): what depth
// measures and in which unit, which normal and in which axes, and how it is stored; and the
// object-coordinates pass. Each needs its pass, and each default is what the pass wrote before
// the option existed.

#include <string>
#include <vector>

#include "batch/OptionEntries.h"
#include "batch/OptionNames.h"

namespace encore::batch::optiontable {

void addPassConventionOptions(std::vector<Entry>& entries) {
    entries.push_back(
        named<DepthKind>("depth-kind", "z",
                         "z: depth is the distance along the camera's axis; ray: along each "
                         "pixel's ray from the camera centre (z / cos of the ray's angle to the "
                         "axis; z for orthographic views)",
                         depthKindNames(),
                         [](BatchOptions& o, DepthKind k) { o.images.depthKind = k; })
            .needing({"depth"}));
    entries.push_back(
        named<DepthUnit>("depth-unit", "normalized",
                         "normalized: depth in the units of the normalised scene (the model fitted "
                         "into the unit box, as the cameras are); model: in the model's own units "
                         "(glTF metres), the normalisation undone (PNG: the same steps, "
                         "depth_scale per model)",
                         depthUnitNames(),
                         [](BatchOptions& o, DepthUnit u) { o.images.depthUnit = u; })
            .needing({"depth"}));
    entries.push_back(
        named<NormalSpace>("normal-space", "world",
                           "world: normals in the glTF world's axes; camera: in each view camera's "
                           "axes, in --camera-convention's (opengl and blender: +z toward the "
                           "camera; opencv: -z)",
                           normalSpaceNames(),
                           [](BatchOptions& o, NormalSpace s) { o.images.normalSpace = s; })
            .needing({"normals"}));
    entries.push_back(
        named<NormalKind>("normal-kind", "shading",
                          "shading: the normal the surface is shaded with (interpolated, "
                          "normal-mapped); geometric: the triangle's own",
                          normalKindNames(),
                          [](BatchOptions& o, NormalKind k) { o.images.normalKind = k; })
            .needing({"normals"}));
    entries.push_back(
        named<NormalFormat>("normal-format", "png8",
                            "png8 or png16: n * 0.5 + 0.5 in 8 or 16 bits (000_normal.png); exr: n "
                            "itself in half floats, alpha the coverage (000_normal.exr)",
                            normalFormatNames(),
                            [](BatchOptions& o, NormalFormat f) { o.images.normalFormat = f; })
            .needing({"normals"}));
    entries.push_back(flag("coordinates",
                           "Also write object coordinates per view (000_coordinates.png: each "
                           "pixel's position in the normalised model box mapped into [0, 1]^3, "
                           "NOCS-style; 16-bit RGBA, alpha the coverage, 0 where empty)",
                           [](BatchOptions& o, bool on) { o.images.coordinates = on; }));
    entries.push_back(
        named<CoordinatesFormat>(
            "coordinates-format", "png16",
            "png16: 16-bit RGBA (000_coordinates.png); exr: half floats "
            "(000_coordinates.exr)",
            coordinatesFormatNames(),
            [](BatchOptions& o, CoordinatesFormat f) { o.images.coordinatesFormat = f; })
            .needing({"coordinates"}));
}

}  // namespace encore::batch::optiontable
