#include "batch/BatchPresets.h"

#include <cmath>
#include <cstdio>

namespace encore::batch {

namespace {

// The sources, cited by every value taken from them.
constexpr const char* kZero123Script =
    "https://github.com/cvlab-columbia/zero123/blob/main/objaverse-rendering/scripts/"
    "blender_script.py";
constexpr const char* kObjaverseXlScript =
    "https://github.com/allenai/objaverse-xl/blob/main/scripts/rendering/blender_script.py";
constexpr const char* kZero123PlusReadme = "https://github.com/SUDO-AI-3D/zero123plus";
constexpr const char* kInstantMeshIssue5 = "https://github.com/TencentARC/InstantMesh/issues/5";
constexpr const char* kInstantMeshCameras =
    "https://github.com/TencentARC/InstantMesh/blob/main/src/utils/camera_util.py";
constexpr const char* kInstantMeshIssue13 = "https://github.com/TencentARC/InstantMesh/issues/13";
constexpr const char* kWonder3dIssue9 = "https://github.com/xxlong0/Wonder3D/issues/9";
constexpr const char* kWonder3dOrtho =
    "https://github.com/xxlong0/Wonder3D/blob/main/render_codes/blenderProc_ortho.py";
constexpr const char* kWonder3dBatch =
    "https://github.com/xxlong0/Wonder3D/blob/main/render_codes/render_batch_ortho.sh";
constexpr const char* kGobjaversePage = "https://aigc3d.github.io/gobjaverse/";
constexpr const char* kGobjaverseReadme =
    "https://github.com/modelscope/richdreamer/tree/main/dataset/gobjaverse";
constexpr const char* kReal3dObjaverse =
    "https://github.com/hwjiang1510/Real3D/blob/main/dataset/objaverse.py";
constexpr const char* kCrmIssue32 = "https://github.com/thu-ml/CRM/issues/32";
constexpr const char* kTrellisRender =
    "https://github.com/microsoft/TRELLIS/blob/main/dataset_toolkits/render.py";
constexpr const char* kMvdreamIssue10 = "https://github.com/MV-Dream/MVDream/issues/10";
constexpr const char* kMvdreamIssue19 = "https://github.com/bytedance/MVDream/issues/19";
constexpr const char* kMvdreamThreestudio = "https://github.com/bytedance/MVDream-threestudio";

std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.6g", value);
    return text;
}

// G-Objaverse's 38 poses, in Encore's azimuths (from glTF's +Z; Blender's azimuth a, measured
// from its +X, is Encore's a + 90): 24 on an orbit, azimuth 15 i, elevation 5 + 25 i / 23,
// distance 1.6450; the top and bottom at 1.6450; 12 on an orbit, azimuth 30 i, elevation
// -5 + 10 i / 11, distance 1.9547.
struct PoseLists {
    std::string azimuths;
    std::string elevations;
    std::string distances;
};

PoseLists gobjaversePoses() {
    PoseLists lists;
    const auto add = [&](double azimuth, double elevation, double distance) {
        const char* comma = lists.azimuths.empty() ? "" : ",";
        lists.azimuths += comma + number(std::fmod(azimuth + 90.0, 360.0));
        lists.elevations += comma + number(elevation);
        lists.distances += comma + number(distance);
    };
    for (int i = 0; i < 24; ++i) {
        add(15.0 * i, 5.0 + 25.0 * i / 23.0, 1.6450);
    }
    add(0.0, 90.0, 1.6450);
    add(0.0, -90.0, 1.6450);
    for (int i = 0; i < 12; ++i) {
        add(30.0 * i, -5.0 + 10.0 * i / 11.0, 1.9547);
    }
    return lists;
}

// 2 atan(16 / 35): a 35 mm lens on a 32 mm sensor, as Zero-1-to-3 and Objaverse-XL render.
constexpr const char* kZero123Fov = "49.1343";

// The presets of image-to-3D pipelines: Zero-1-to-3, Zero123++, InstantMesh, Wonder3D.
void addViewSynthesisPresets(std::vector<BatchPreset>& presets) {
    const std::string zero123Fov = kZero123Fov;
    presets.push_back(
        {"zero123",
         "Zero-1-to-3's Objaverse renders: 12 random views on a sphere shell, a 35 mm lens",
         {{"random-views", "12", std::string(kZero123Script) + " (12 renders per object)"},
          {"distance", "1.5:2.2",
           std::string(kZero123Script) + " (sample_spherical(radius_min=1.5, radius_max=2.2))"},
          {"fov", zero123Fov,
           std::string(kZero123Script) +
               " (cam.data.lens = 35, sensor_width = 32: 2 atan(16 / 35) = 49.13 degrees)"},
          {"background", "transparent",
           std::string(kZero123Script) + " (render.film_transparent = True)"},
          {"layout", "objaverse", std::string(kZero123Script) + " (np.save of each view's RT)"}},
         "Zero123's script normalises with the scene's largest side too, but lights with its own "
         "area lights, not Encore's studio environment."});
    presets.push_back(
        {"zero123plus",
         "Zero123++ v1.2's six output views: fixed azimuths and alternating elevations, FOV 30",
         {{"azimuths", "30,90,150,210,270,330",
           std::string(kZero123PlusReadme) +
               " (README, camera poses: azimuths relative to the input view)"},
          {"elevations", "20,-10,20,-10,20,-10",
           std::string(kInstantMeshIssue5) +
               " (quoting Zero123++'s README: v1.2 elevations 20, -10; v1.1's 30, -20)"},
          {"fov", "30",
           std::string(kInstantMeshIssue5) +
               " (quoting Zero123++'s README: v1.2 field of view 30 degrees)"},
          {"distance", "2",
           std::string(kInstantMeshCameras) +
               " (get_zero123plus_input_cameras: radius 4.0 for a model in [-1, 1], 2.0 in the "
               "unit box)"}},
         "Azimuth 0 is the input view: the model's front (+Z) here. Zero123++ publishes no "
         "camera distance; InstantMesh's reconstruction of its views uses the one above."});
    presets.push_back(
        {"instantmesh",
         "InstantMesh's reconstruction training renders: 32 views, distance 2.0-3.5 in [-1, 1]",
         {{"views", "32", std::string(kInstantMeshIssue13) + " (32 views per model)"},
          {"distance", "1:1.75",
           std::string(kInstantMeshIssue13) +
               " (distances 2.0-3.5 for a model in [-1, 1]: 1.0-1.75 in the unit box)"},
          {"elevation", "-22:53",
           std::string(kInstantMeshIssue13) +
               " (camera heights -0.75 to 1.6: asin(-0.75 / 2) and asin(1.6 / 2) at distance "
               "2.0)"},
          {"fov", "50", std::string(kInstantMeshIssue13) + " (fov=50)"}},
         "InstantMesh draws free viewpoints by camera height; Encore spreads the 32 azimuths "
         "evenly and draws the elevation per view from the range the heights give at the "
         "nearest distance. Its Zero123++ fine-tuning renders (FOV 30) are the zero123plus "
         "preset."});
    presets.push_back(
        {"wonder3d",
         "Wonder3D's six orthographic views at elevation 0",
         {{"projection", "orthographic", std::string(kWonder3dOrtho) + " (camera type ORTHO)"},
          {"ortho-scale", "1.35", std::string(kWonder3dBatch) + " (--ortho_scale 1.35)"},
          {"azimuths", "0,45,90,180,-90,-45",
           std::string(kWonder3dIssue9) + " (front, front right, right, back, left, front left)"},
          {"elevations", "0", std::string(kWonder3dIssue9) + " (the six elevations are zero)"},
          {"distance", "2", std::string(kWonder3dOrtho) + " (radius = 2.0)"},
          {"normals", "true", std::string(kWonder3dOrtho) + " (enable_normals_output)"}},
         "Wonder3D's normals are in the front view's camera frame and Encore's normal pass is "
         "in world space (--normal-space is not there yet); Wonder3D scales the bounding box's "
         "diagonal to 1, Encore its largest side, so its objects look up to 1.7 times smaller "
         "than these."});
}

// The presets of datasets and text-to-3D pipelines: G-Objaverse, TRELLIS, MVDream, Objaverse-XL.
void addDatasetPresets(std::vector<BatchPreset>& presets) {
    const std::string zero123Fov = kZero123Fov;
    const PoseLists gobjaverse = gobjaversePoses();
    presets.push_back(
        {"gobjaverse",
         "G-buffer Objaverse's 38 poses at 512 x 512 with every G-buffer pass",
         {{"azimuths", gobjaverse.azimuths,
           std::string(kGobjaversePage) +
               " (24 views at 15-degree steps, top and bottom, 12 at 30-degree steps; Blender's "
               "azimuth + 90)"},
          {"elevations", gobjaverse.elevations,
           std::string(kGobjaversePage) + " (5 to 30 degrees, +-90, -5 to 5 degrees)"},
          {"distances", gobjaverse.distances,
           std::string(kReal3dObjaverse) + " (orbits at 1.6450 and 1.9547, object in [-0.5, 0.5])"},
          {"fov", "39.5978",
           std::string(kCrmIssue32) +
               " (Blender's default camera, 0.6911 rad, as the x_fov of the camera files)"},
          {"size", "512", std::string(kGobjaverseReadme) + " (campos_512_v4)"},
          {"albedo", "true", std::string(kGobjaverseReadme) + " (00000_albedo.png)"},
          {"hdr", "true", std::string(kGobjaverseReadme) + " (00000_hdr.exr)"},
          {"material", "true", std::string(kGobjaverseReadme) + " (00000_mr.png)"},
          {"normals", "true", std::string(kGobjaverseReadme) + " (00000_nd.exr)"},
          {"depth", "true", std::string(kGobjaverseReadme) + " (00000_nd.exr)"},
          {"depth-format", "exr", std::string(kGobjaverseReadme) + " (00000_nd.exr)"},
          {"camera-convention", "opencv",
           std::string(kReal3dObjaverse) + " (reads the camera files as OpenCV camera-to-world)"},
          {"layout", "gobjaverse",
           std::string(kGobjaverseReadme) +
               " (00000/00000.json: camera information; its fields as Real3D reads them)"}},
         "G-Objaverse puts each view in a folder of its own (00000/00000.png) and normals with "
         "depth in one EXR; Encore writes the views side by side (000.png, 000.json) and "
         "separate normal (8-bit PNG, world space) and depth (EXR) files, and its material pass "
         "holds occlusion beside roughness and metallic. The field of view is Blender's "
         "default, which the public reproductions of the layout use (0.7 rad rounded)."});
    presets.push_back(
        {"trellis",
         "TRELLIS's 150 views on a Hammersley sphere, radius 2, FOV 40, 512 x 512",
         {{"views", "150", std::string(kTrellisRender) + " (--num_views default 150)"},
          {"camera-distribution", "hammersley",
           std::string(kTrellisRender) + " (sphere_hammersley_sequence with a random offset)"},
          {"distance", "2", std::string(kTrellisRender) + " (radius = [2] * num_views)"},
          {"fov", "40", std::string(kTrellisRender) + " (fov = 40 / 180 * pi)"},
          {"size", "512", std::string(kTrellisRender) + " (--resolution 512)"}},
         "TRELLIS's offsets come from NumPy's generator, Encore's from --seed: the same point "
         "set, turned differently per model."});
    presets.push_back(
        {"mvdream",
         "MVDream's renders: 32 azimuths, elevation 0-30, distance 0.9-1.1 relative, FOV 15-60",
         {{"views", "32",
           std::string(kMvdreamIssue19) + " (32 uniformly distributed azimuths from 0)"},
          {"elevation", "0:30", std::string(kMvdreamIssue10) + " (paper section 4.1)"},
          {"distance", "0.9:1.1", std::string(kMvdreamIssue10) + " (paper section 4.1)"},
          {"distance-relative-to-fov", "true",
           std::string(kMvdreamThreestudio) +
               " (its random multiview cameras: relative_radius, distance / tan(fovy / 2))"},
          {"fov", "15:60", std::string(kMvdreamIssue10) + " (paper section 4.1)"}},
         "MVDream draws the elevation, distance and field of view once per object, shared by its "
         "views; Encore draws them per view."});
    presets.push_back(
        {"objaverse-xl",
         "The Objaverse-XL rendering script: 12 views on a sphere shell, .npy camera matrices",
         {{"random-views", "12", std::string(kObjaverseXlScript) + " (--num_renders 12)"},
          {"distance", "1.5:2.2",
           std::string(kObjaverseXlScript) + " (sample_spherical(radius_min=1.5, radius_max=2.2))"},
          {"fov", zero123Fov,
           std::string(kObjaverseXlScript) + " (cam.data.lens = 35, sensor_width = 32)"},
          {"layout", "objaverse",
           std::string(kObjaverseXlScript) + " (get_3x4_RT_matrix_from_blender, np.save)"}},
         "The script's random area lights are not drawn; metadata.json holds Encore's facts, "
         "not the script's."});
}

std::vector<BatchPreset> describePresets() {
    std::vector<BatchPreset> presets;
    addViewSynthesisPresets(presets);
    addDatasetPresets(presets);
    return presets;
}

}  // namespace

std::span<const BatchPreset> batchPresets() {
    static const std::vector<BatchPreset> presets = describePresets();
    return presets;
}

const BatchPreset* findPreset(std::string_view name) {
    for (const BatchPreset& preset : batchPresets()) {
        if (preset.name == name) {
            return &preset;
        }
    }
    return nullptr;
}

std::vector<std::string> presetNames() {
    std::vector<std::string> names;
    for (const BatchPreset& preset : batchPresets()) {
        names.push_back(preset.name);
    }
    return names;
}

std::string presetListing() {
    std::string text;
    for (const BatchPreset& preset : batchPresets()) {
        text += preset.name + ": " + preset.summary + "\n";
        for (const PresetValue& value : preset.values) {
            text += "  --" + value.option + (value.value == "true" ? "" : " " + value.value) +
                    "\n      " + value.source + "\n";
        }
        if (!preset.notHonoured.empty()) {
            text += "  not reproduced: " + preset.notHonoured + "\n";
        }
        text += "\n";
    }
    text += "An option given beside --preset replaces the preset's value.\n";
    return text;
}

std::string presetsMarkdown() {
    std::string table = "| Preset | Options | Sources | Not reproduced |\n|---|---|---|---|\n";
    for (const BatchPreset& preset : batchPresets()) {
        std::string options;
        std::string sources;
        for (const PresetValue& value : preset.values) {
            options += (options.empty() ? "" : " ") + ("`--" + value.option) +
                       (value.value == "true" ? "" : " " + value.value) + "`";
            sources +=
                (sources.empty() ? "" : "<br>") + ("`--" + value.option + "`: ") + value.source;
        }
        table += "| `" + preset.name + "`: " + preset.summary + " | " + options + " | " + sources +
                 " | " + preset.notHonoured + " |\n";
    }
    return table;
}

}  // namespace encore::batch
