// The Python module `encore`: the C++ library's batch rendering for Python code (data loaders,
// task systems). It wraps encore::batch and encore::render, not the executable.
//
//   renderer = encore.Renderer()              # one GPU device
//   scene = renderer.load("model.glb")        # encore.LoadError with the loader's message
//   images, intrinsics, cameras = renderer.render_views(scene, views=12, size=512)
//   renderer.batch("models/", "out/", views=12)  # the job of `encore batch`, returns its summary
//
// The GIL is released while files load and while the GPU renders. The package around it
// (python/encore/__init__.py) adds encore.batch and encore.dask.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "BatchArguments.h"
#include "BatchKeywords.h"
#include "ModuleErrors.h"
#include "Renderer.h"
#include "batch/BatchOptionTable.h"
#include "encore/batch/ViewRig.h"
#include "encore/gpu/Context.h"

namespace py = pybind11;

namespace {

// Renderer.batch's docstring: its keywords from the batch's description of its options.
const std::string& batchDocstring() {
    static const std::string text =
        "batch(inputs, output, **options)\n\n"
        "Runs the job of `encore batch` on this renderer's device: `inputs` is what the command "
        "takes (folder, list file, model) or (path, name) pairs from discover_inputs. Returns the "
        "summary (models rendered, failed, skipped; views; seconds; time per stage; failures). "
        "The options are `encore batch`'s, as keywords (docs/batch.md#options); None leaves an "
        "option at its default; samples defaults to the renderer's and the strategy is the "
        "renderer's. An unknown keyword raises TypeError naming the nearest one, a value an "
        "option does not take ValueError. The GIL is released while it runs.\n\n"
        "Keyword options:\n" +
        encore::batch::batchOptionsDocstring() + encore::python::batchKeywordsDocstring();
    return text;
}

// encore.batch_options(): the description of every option batch() takes.
py::list batchOptions() {
    py::list list;
    for (const encore::batch::BatchOptionDescription& option :
         encore::batch::batchOptionDescriptions()) {
        if (!option.python) {
            continue;
        }
        py::dict entry;
        entry["keyword"] = option.pythonKeyword();
        entry["command_line"] =
            option.commandLine ? py::object(py::str("--" + option.name)) : py::object(py::none());
        entry["default"] = option.defaultValue.empty() ? py::object(py::none())
                                                       : py::object(py::str(option.defaultValue));
        entry["choices"] = option.choices;
        entry["help"] = option.help;
        list.append(entry);
    }
    return list;
}

void bindScene(py::module_& module) {
    using namespace encore::python;
    py::class_<Scene>(module, "Scene", "A loaded glTF model (renderer.load).")
        .def_property_readonly("path",
                               [](const Scene& scene) { return scene.data->sourcePath.string(); })
        .def_property_readonly("bounds",
                               [](const Scene& scene) {
                                   const auto& bounds = scene.data->bounds;
                                   return py::make_tuple(
                                       py::make_tuple(bounds.min.x, bounds.min.y, bounds.min.z),
                                       py::make_tuple(bounds.max.x, bounds.max.y, bounds.max.z));
                               })
        .def_property_readonly(
            "variants", [](const Scene& scene) { return scene.data->variants; },
            "The names of the model's KHR_materials_variants variants, by index (render_views' "
            "and batch's variant=); empty without the extension.");
}

void bindRenderer(py::module_& module) {
    using namespace encore::python;
    py::class_<Renderer>(module, "Renderer",
                         "One GPU device (Vulkan) rendering models from a view rig.")
        .def(py::init<std::uint32_t, std::optional<std::size_t>,
                      const std::optional<std::string>&>(),
             py::arg("samples") = 4, py::arg("device") = py::none(),
             py::arg("strategy") = py::none(),
             "A renderer on adapter `device` of encore.adapters() (default: the ENCORE_DEVICE "
             "environment variable, else 0, the adapter Dawn prefers), drawing with `strategy` "
             "(a name of `encore --help`'s list, e.g. \"visibility\" or \"gpu-culling-bundles\"; "
             "default or \"auto\": render_views draws with bundles, batch chooses per model "
             "as `encore batch` does by default).")
        .def("load", &Renderer::load, py::arg("path"), py::arg("allow_uris_outside") = false,
             "Loads a .gltf or .glb file; raises encore.LoadError with the loader's message. "
             "Its buffers and images are read only from inside its folder unless "
             "allow_uris_outside=True (trusted files only: docs/batch.md).")
        .def("render_views", &Renderer::renderViews, py::arg("scene"), py::arg("views") = 12,
             py::arg("size") = 512, py::arg("elevation") = 30.0f, py::arg("distance") = 1.5f,
             py::arg("fov") = py::none(), py::arg("random") = false, py::arg("seed") = 0,
             py::arg("normalize") = true, py::arg("normals") = false, py::arg("depth") = false,
             py::arg("name") = "", py::arg("variant") = py::none(), py::arg("passes") = py::none(),
             py::arg("segmentation_by") = "node", py::arg("environment") = py::none(),
             py::arg("environment_intensity") = 1.0f, py::arg("environment_rotation") = 0.0f,
             py::arg("exposure") = 1.0f, py::arg("tone_mapping") = "neutral",
             py::arg("background") = "transparent", py::arg("pass_frames") = false,
             py::arg("depth_kind") = "z", py::arg("depth_unit") = "normalized",
             py::arg("normal_space") = "world", py::arg("normal_kind") = "shading",
             py::arg("normal_format") = "png8", py::arg("camera_convention") = py::none(),
             py::arg("camera_distribution") = py::none(), py::arg("projection") = "perspective",
             py::arg("ortho_scale") = encore::batch::kDefaultOrthoScale,
             py::arg("azimuths") = py::none(), py::arg("elevations") = py::none(),
             py::arg("distances") = py::none(), py::arg("poses") = py::none(),
             py::arg("point_cloud") = 0,
             "Renders `views` RGBA views (straight alpha, transparent background) of the scene "
             "normalised into a unit box, from an orbit `elevation` degrees above the horizon or "
             "(random=True) directions uniform on the sphere drawn from `seed` (and, as `encore "
             "batch` "
             "draws them, the model's output `name`). Returns (images "
             "uint8 (N, H, W, 4), intrinsics float64 (3, 3) in pixels, camera-to-world float64 "
             "(N, 4, 4) in camera_convention's axes), as `encore batch` writes them. `fov` is "
             "horizontal, in degrees (default: a 35 mm lens on a 32 mm sensor). normals=True "
             "appends the world-space normals, uint8 (N, H, W, 4) as n * 0.5 + 0.5 with the "
             "views' alpha, and depth=True (after them) the distances along each camera's axis, "
             "float32 (N, H, W), 0 where less than half of a pixel is covered: the pixels of "
             "`encore batch --normals --depth`'s 000_normal.png and of 000_depth.png times its "
             "depth_scale. variant= draws a KHR_materials_variants variant (its name or index, "
             "scene.variants lists them; ValueError for one the model lacks) instead of the "
             "default materials. passes=(\"rgba\", \"albedo\", \"normal\", \"material\", "
             "\"segmentation\", \"depth\", \"hdr\", \"coordinates\") (any of them, in any "
             "order) returns a dict instead: each pass's array (uint8 (N, H, W, 4) for rgba, "
             "albedo, normal and material; depth float32 (N, H, W), inf where empty; "
             "segmentation uint16 (N, H, W), 1 + the node (segmentation_by=\"mesh\", "
             "\"material\") index, exact at any sample count (one sample of each pixel); hdr "
             "float32 (N, H, W, 4), linear and "
             "premultiplied; coordinates float32 (N, H, W, 4), each pixel's position in the "
             "normalised box moved into [0, 1]^3 with the coverage as alpha, 0 where empty) with "
             "\"intrinsics\" and \"cameras\", as `encore batch` writes "
             "them (docs/batch.md#passes); they are drawn in the colour's render pass, or with "
             "pass_frames=True one frame per pass (the same values, slower). The passes' "
             "conventions are `encore batch`'s (docs/batch.md#conventions) and need passes=: "
             "depth_kind (z: along the camera's axis, ray: along the pixel's ray), depth_unit "
             "(normalized, model), normal_space (world, camera: the axes of camera_convention's "
             "cameras), normal_kind (shading, geometric) and normal_format (png8: uint8 n * 0.5 "
             "+ 0.5, png16: uint16, exr: float32 n; the coverage as alpha). camera_convention "
             "(opengl, opencv, blender; default opengl) gives the returned cameras in "
             "transforms.json's axes. "
             "The views as `encore batch` places them: camera_distribution (orbit, sphere, "
             "upper-hemisphere, hammersley, fibonacci; random=True is sphere), azimuths, "
             "elevations and distances (sequences of one value per view, or one for all, "
             "replacing `views`), projection (perspective, orthographic: the intrinsics then "
             "hold pixels per unit in place of focal lengths) and ortho_scale; or poses, a file of "
             "cameras as `encore batch --poses` reads it (transforms.json, a JSON list, .npy; "
             "in camera_convention's axes when given). point_cloud=P (with passes=) adds "
             "\"point_cloud\": the points of `encore batch --point-cloud P`'s points.ply for "
             "the model of output `name`, a dict of positions and normals float32 (P, 3) in the "
             "normalised frame and colors uint8 (P, 4), sRGB. Shading as `encore "
             "render`'s: environment (an .hdr "
             "file), environment_intensity, environment_rotation (degrees), exposure, "
             "tone_mapping (neutral, aces, none), background (transparent, env, #rrggbb). The GIL "
             "is released while rendering.")
        .def("batch", &Renderer::runBatch, py::arg("inputs"), py::arg("output"),
             batchDocstring().c_str())
        .def_property_readonly("samples",
                               [](const Renderer& renderer) { return renderer.samples(); })
        .def_property_readonly("adapter", &Renderer::adapter)
        .def_property_readonly("strategy", &Renderer::strategy,
                               "The strategy given to the constructor, or None.")
        .def_property_readonly("device", &Renderer::device,
                               "The index of the renderer's adapter in encore.adapters().")
        .def_property_readonly(
            "batch_renderers_created",
            [](Renderer& renderer) { return renderer.batchCounts().renderers; },
            "How many times batch() built its renderer (render target, pipelines): once for "
            "calls with the same size, samples and normals/depth, again when those change.")
        .def_property_readonly(
            "batch_environments_created",
            [](Renderer& renderer) { return renderer.batchCounts().environments; },
            "How many times batch() computed the environment maps: once for every call so far.");
}

void bindFunctions(py::module_& module) {
    using namespace encore::python;
    module.def(
        "adapters",
        [] {
            py::list list;
            for (const encore::gpu::AdapterDescription& adapter :
                 valueOrThrow(encore::gpu::listAdapters())) {
                py::dict entry;
                entry["index"] = adapter.index;
                entry["name"] = adapter.name;
                entry["type"] = encore::gpu::adapterTypeName(adapter.adapterType);
                entry["backend"] = encore::gpu::backendName(adapter.backend);
                entry["driver"] = adapter.driver;
                entry["summary"] = adapter.summary();
                list.append(entry);
            }
            return list;
        },
        "The GPU adapters, as `encore info` lists them: dicts of index, name, type ('discrete "
        "GPU', 'CPU', ...), backend, driver and summary. Renderer(device=index) picks one.");
    module.def("batch_options", &batchOptions,
               "The options Renderer.batch and encore.batch take, as dicts of keyword, "
               "command_line (`encore batch`'s name, or None), default (as the command line "
               "writes it, or None), choices and help: the description `encore batch --help` and "
               "docs/batch.md are made from.");
    module.def("discover_inputs", &discoverInputs, py::arg("input"),
               "The models `encore batch INPUT` renders, as (path, output name) pairs: INPUT is a "
               "folder (searched recursively), a list file (one path per line, or a JSON array), "
               "a model, or a sequence of model paths (named relative to the deepest folder that "
               "holds them all).");
}

}  // namespace

PYBIND11_MODULE(_encore, module) {
    using namespace encore::python;
    module.doc() = "Encore: glTF 2.0 rendering with WebGPU (Dawn), for datasets of rendered views.";
    static py::exception<EncoreError> error(module, "Error", PyExc_RuntimeError);
    static py::exception<LoadError> loadError(module, "LoadError", error.ptr());
    py::register_exception_translator([](std::exception_ptr pointer) {
        try {
            if (pointer) {
                std::rethrow_exception(pointer);
            }
        } catch (const LoadError& caught) {
            PyErr_SetString(loadError.ptr(), caught.what());
        } catch (const EncoreError& caught) {
            PyErr_SetString(error.ptr(), caught.what());
        }
    });

    bindScene(module);
    bindRenderer(module);
    bindFunctions(module);
}
