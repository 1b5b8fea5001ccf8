#include "batch/BatchOptionTable.h"

#include <algorithm>
#include <limits>
#include <memory>

#include "batch/BatchPresets.h"
#include "batch/OptionEntries.h"
#include "batch/OptionNames.h"
#include "batch/OptionValues.h"
#include "encore/batch/BatchLighting.h"
#include "encore/image/HdrImage.h"
#include "encore/render/StrategyKind.h"

namespace encore::batch {

namespace {

using namespace optiontable;

std::string strategyNames() {
    std::string names = "auto";
    for (render::StrategyKind kind : render::allStrategies()) {
        names += ", " + std::string(render::strategyName(kind));
    }
    return names;
}

// The images' size and samples.
void addImageOptions(std::vector<Entry>& entries) {
    entries.push_back(
        text("size", OptionForm::ImageSize, "W|WxH", "Image size W or WxH in pixels",
             [](BatchOptions& o, std::string_view value, std::string_view shown) -> Result<void> {
                 ENCORE_TRY_ASSIGN(auto size, parseImageSize(value, shown));
                 std::tie(o.width, o.height) = size;
                 return Result<void>{};
             }));
    entries.back().description.defaultValue = "512";
    {
        Entry samples =
            wholeNumber("samples", "", "4", "Multisampling: 1 or 4", 1, 4,
                        [](BatchOptions& o, std::uint64_t n) { o.samples = std::uint32_t(n); });
        samples.description.choices = {"1", "4"};
        auto parse = samples.description.apply;
        samples.description.apply = [parse](BatchOptions& o, std::string_view value,
                                            std::string_view shown) -> Result<void> {
            if (value != "1" && value != "4") {
                return makeError(
                    ErrorCode::InvalidArgument,
                    std::string(shown) + " takes 1 or 4 (not '" + std::string(value) + "').");
            }
            return parse(o, value, shown);
        };
        entries.push_back(std::move(samples));
    }
}

// How the models are drawn.
void addStrategyOptions(std::vector<Entry>& entries) {
    entries.push_back(
        text("strategy", OptionForm::Text, "NAME",
             "Rendering strategy of every model, or auto (the default): per model, visibility on "
             "a GPU for models of at least " +
                 std::to_string(kAutoVisibilityTriangles) + " triangles (" +
                 std::to_string(kAutoVisibilityTrianglesOneSample) +
                 " at --samples 1) and, at --samples 4, for those of only opaque, static "
                 "triangles whatever their size, else bundles (gpu-culling-bundles with "
                 "--lod-error); bundles on a CPU and with extra images; metadata.json names the "
                 "choice. Python: the Renderer's strategy",
             [](BatchOptions& o, std::string_view value, std::string_view shown) -> Result<void> {
                 if (value == "auto") {
                     o.strategy.reset();
                     o.chooseStrategyPerModel = true;
                     return {};
                 }
                 const auto choice = render::strategyChoiceFromName(value);
                 if (!choice) {
                     return makeError(ErrorCode::InvalidArgument,
                                      std::string(shown) + " takes " + strategyNames() +
                                          ", or a direct one with +bundle (not '" +
                                          std::string(value) + "').");
                 }
                 o.strategy = *choice;
                 return {};
             })
            .shortName('s')
            .commandLineOnly());
    entries.back().description.defaultValue = "auto";
    entries.push_back(wholeNumber(
        "visibility-from-triangles", "N", "",
        "With --strategy auto: the triangles (summed over the "
        "instances) from which a model is drawn with visibility, on "
        "any adapter that has the feature (a CPU too), replacing auto's "
        "rule for opaque, static models. Default: " +
            std::to_string(kAutoVisibilityTriangles) + " on a GPU (" +
            std::to_string(kAutoVisibilityTrianglesOneSample) + " at --samples 1)",
        0, kAll, [](BatchOptions& o, std::uint64_t n) { o.visibilityFromTriangles = n; }));
    entries.push_back(number("lod-error", "PIXELS", "",
                             "Draw each instance at the coarsest level of detail whose "
                             "simplification error stays under this many pixels in the nearest "
                             "view (levels are built at load; a gpu-culling strategy or "
                             "visibility chooses them). Default: full detail",
                             0.0f, kNoLimit,
                             [](BatchOptions& o, float v) { o.lodErrorPixels = v; }));
}

// What a bad or hostile file may do.
void addRobustnessOptions(std::vector<Entry>& entries) {
    entries.push_back(flag("strict", "Treat loader warnings as errors (the model fails)",
                           [](BatchOptions& o, bool on) { o.strict = on; }));
    entries.push_back(number("model-timeout", "SECONDS", "600",
                             "Abandon a model still loading or drawing after this many seconds "
                             "of work on it (failures.jsonl stage timeout) and go on; 0: no limit",
                             0.0f, kNoLimit,
                             [](BatchOptions& o, float v) { o.modelTimeoutSeconds = v; }));
    entries.push_back(wholeNumber(
        "max-texture-size", "PIXELS", std::to_string(kDefaultMaxTextureSize),
        "Downscale larger images while loading (listed in "
        "metadata.json's imagesDownscaled); 0: keep every size",
        0, kAll32, [](BatchOptions& o, std::uint64_t n) { o.maxTextureSize = std::uint32_t(n); }));
    entries.push_back(flag("allow-uris-outside",
                           "Let models read buffers and images outside their own folder "
                           "(absolute paths, '..', links that lead out): for trusted local trees "
                           "only",
                           [](BatchOptions& o, bool on) { o.allowUrisOutside = on; })
                          .commandLineGlobal());
}

// KHR_materials_variants.
void addMaterialOptions(std::vector<Entry>& entries) {
    entries.push_back(
        text("variant", OptionForm::Text, "N|NAME",
             "Draw every model in this KHR_materials_variants variant (index or "
             "name) into OUT/<name>@<variant>; a model without it fails",
             [](BatchOptions& o, std::string_view value, std::string_view) -> Result<void> {
                 o.variant = std::string(value);
                 return Result<void>{};
             })
            .excluding({"variants"}));
    {
        Entry variants = text("variants", OptionForm::Text, "",
                              "all: draw every model with its default materials into "
                              "OUT/<name> and in each of its variants into "
                              "OUT/<name>@<variant>, each a sample of its own",
                              [](BatchOptions& o, std::string_view value,
                                 std::string_view shown) -> Result<void> {
                                  if (value != "all") {
                                      return makeError(ErrorCode::InvalidArgument,
                                                       std::string(shown) + " takes all (not '" +
                                                           std::string(value) + "').");
                                  }
                                  o.allVariants = true;
                                  return {};
                              })
                             .excluding({"variant"});
        variants.description.choices = {"all"};
        entries.push_back(std::move(variants));
    }
}

// Threads, memory and renderers.
void addPipelineOptions(std::vector<Entry>& entries) {
    entries.push_back(wholeNumber("jobs", "N", "",
                                  "Threads for loading and encoding (default or 0: all cores)", 0,
                                  1024, [](BatchOptions& o, std::uint64_t n) { o.jobs = n; })
                          .shortName('j'));
    entries.push_back(
        wholeNumber("memory-limit", "MIB", "2048",
                    "MiB the models hold decoded at once (loaded ahead of the GPU "
                    "or loading), at most; a model alone past it fails",
                    1, std::uint64_t{1} << 24,
                    [](BatchOptions& o, std::uint64_t n) { o.memoryLimitBytes = n << 20; })
            .keyword("memory_limit_mib"));
    entries.push_back(wholeNumber("renderers", "N", std::to_string(kDefaultRenderers),
                                  "Models on the device at once: the next uploads while the GPU "
                                  "draws the others (1: one after the other)",
                                  1, kMaxRenderers,
                                  [](BatchOptions& o, std::uint64_t n) { o.renderers = n; }));
}

// The images beside the colour ones.
void addPassOptions(std::vector<Entry>& entries) {
    entries.push_back(flag("normals",
                           "Also write world-space normals per view (000_normal.png: n * 0.5 + "
                           "0.5)",
                           [](BatchOptions& o, bool on) { o.images.normals = on; }));
    entries.push_back(flag("depth",
                           "Also write 16-bit depth per view (000_depth.png; depth_scale in "
                           "transforms.json)",
                           [](BatchOptions& o, bool on) { o.images.depth = on; }));
    entries.push_back(flag("albedo",
                           "Also write the base colour per view (000_albedo.png: texture x factor "
                           "x vertex colour, sRGB)",
                           [](BatchOptions& o, bool on) { o.images.albedo = on; }));
    entries.push_back(flag("material",
                           "Also write occlusion, roughness and metallic per view "
                           "(000_material.png, linear R, G, B)",
                           [](BatchOptions& o, bool on) { o.images.material = on; }));
    entries.push_back(flag("segmentation",
                           "Also write 16-bit ids per view (000_segmentation.png: 0 background, "
                           "else 1 + the node index; names in transforms.json); at 4 samples each "
                           "pixel's id is one sample's, exact, while the colour is antialiased",
                           [](BatchOptions& o, bool on) { o.images.segmentation = on; }));
    entries.push_back(named<SegmentationBy>(
                          "segmentation-by", "node",
                          "What a segmentation id counts: node, mesh or material",
                          segmentationByNames(),
                          [](BatchOptions& o, SegmentationBy by) { o.images.segmentationBy = by; })
                          .needing({"segmentation"}));
    entries.push_back(
        named<DepthFormat>("depth-format", "png",
                           "png: 16-bit steps of depth_scale; exr: 32-bit float distances along "
                           "the camera axis, infinity where empty (000_depth.exr)",
                           depthFormatNames(),
                           [](BatchOptions& o, DepthFormat f) { o.images.depthFormat = f; })
            .needing({"depth"}));
    addPassConventionOptions(entries);
    entries.push_back(flag("hdr",
                           "Also write the linear colour before exposure and tone mapping per "
                           "view (000_hdr.exr, half float, premultiplied alpha)",
                           [](BatchOptions& o, bool on) { o.images.hdr = on; }));
    entries.push_back(wholeNumber(
        "point-cloud", "N", "",
        "Also write OUT/<name>/points.ply: N points drawn uniformly by area from the model's "
        "surface in the normalised frame, with normals and base colours (binary little-endian "
        "PLY), drawn from --seed and the model's name",
        1, 100'000'000,
        [](BatchOptions& o, std::uint64_t n) { o.pointCloudPoints = std::uint32_t(n); }));
    entries.push_back(flag("pass-frames",
                           "Draw each pass as one more frame through a debug channel instead of "
                           "in the colour frame's render pass (the same images, slower: for "
                           "comparisons)",
                           [](BatchOptions& o, bool on) {
                               o.images.drawing = on ? PassDrawing::Frames : PassDrawing::Targets;
                           }));
}

// What is written, and how.
void addOutputOptions(std::vector<Entry>& entries) {
    entries.push_back(number("top-light", "LUX", "",
                             "Add a directional light shining straight down, this many lux (the "
                             "dataset scripts' light from above)",
                             0.0f, kNoLimit, [](BatchOptions& o, float v) { o.topLightLux = v; }));
    entries.push_back(named<image::PngCompression>(
        "png-compression", "small",
        "small: Paeth and runs for 8-bit images, libdeflate for 16-bit depth (the default); "
        "fast: about a third less encoding time for views 25-30% larger (depth nearly 3x), when "
        "encoding limits the batch",
        pngCompressionNames(),
        [](BatchOptions& o, image::PngCompression c) { o.pngCompression = c; }));
    entries.push_back(named<PngFiltering>(
        "png-filtering", "auto",
        "Where the PNG rows are filtered and the passes' samples made: gpu (a compute pass; the "
        "pool only compresses), cpu, or auto: the GPU unless the adapter is a CPU (lavapipe). "
        "The files are the same either way",
        pngFilteringNames(), [](BatchOptions& o, PngFiltering f) { o.pngFiltering = f; }));
    entries.push_back(named<OutputLayout>(
        "layout", "nerf",
        "nerf: images and transforms.json; objaverse: also a 000.npy camera matrix per view, as "
        "the Objaverse-XL scripts write them; gobjaverse: also a 000.json camera per view, as "
        "G-Objaverse's (origin, x, y, z, x_fov, y_fov)",
        outputLayoutNames(), [](BatchOptions& o, OutputLayout l) { o.layout = l; }));
    entries.push_back(wholeNumber(
        "shards", "N", "",
        "Write WebDataset .tar shards (OUT/shard-000000.tar ...: "
        "<name>.000.png, <name>.transforms.json, ...) instead of a "
        "folder per model, about this many",
        1, 1'000'000, [](BatchOptions& o, std::uint64_t n) { o.shards = std::uint32_t(n); }));
    entries.push_back(
        text("shard-size", OptionForm::ByteSize, "BYTES",
             "Write WebDataset .tar shards, each finished once it holds this much "
             "(1GiB, 500MB, ...)",
             [](BatchOptions& o, std::string_view value, std::string_view shown) -> Result<void> {
                 ENCORE_TRY_ASSIGN(o.shardBytes, parseByteSize(value, shown));
                 return Result<void>{};
             }));
    entries.push_back(wholeNumber(
        "blank-threshold", "PIXELS", std::to_string(kDefaultBlankThreshold),
        "A view covering fewer pixels is blank: listed in metadata.json "
        "(and a failure with --strict); 0: none is",
        0, kAll32, [](BatchOptions& o, std::uint64_t n) { o.blankThreshold = std::uint32_t(n); }));
    entries.push_back(flag("failure-log",
                           "Write OUTPUT/failures.jsonl (False: the failures only in the "
                           "summary, for callers that run several batches into one folder)",
                           [](BatchOptions& o, bool on) { o.writeFailureLog = on; })
                          .pythonOnly());
    entries.back().description.defaultValue = "true";
}

// The options of a batch, in the order they are applied: an option that overrides another
// (random-views over views) comes after it.
std::vector<Description> describeOptions() {
    std::vector<Entry> entries;
    {
        Entry preset = text(
            "preset", OptionForm::Text, "NAME",
            "Start from a published pipeline's options (docs/batch.md, Presets); an option given "
            "beside it replaces the preset's value. `encore batch --preset list` prints them with "
            "their sources",
            [](BatchOptions& o, std::string_view value, std::string_view) -> Result<void> {
                o.preset = std::string(value);  // Its options were applied with the others.
                return Result<void>{};
            });
        preset.description.choices = presetNames();
        entries.push_back(std::move(preset));
    }
    addCameraOptions(entries);
    addImageOptions(entries);
    addStrategyOptions(entries);
    addRobustnessOptions(entries);
    addMaterialOptions(entries);
    addPipelineOptions(entries);
    addPassOptions(entries);
    addOutputOptions(entries);
    addShadingOptions(entries);
    std::vector<Description> descriptions;
    for (Entry& entry : entries) {
        descriptions.push_back(std::move(entry.description));
    }
    return descriptions;
}

bool givenOn(const GivenOption& given) {
    return given.option->form != OptionForm::Flag || given.value != "false";
}

const GivenOption* findGiven(std::span<const GivenOption> given, std::string_view name) {
    const auto found = std::find_if(given.begin(), given.end(), [&](const GivenOption& entry) {
        return entry.option->name == name && givenOn(entry);
    });
    return found == given.end() ? nullptr : &*found;
}

// What a Python docstring and the Markdown table call the value.
std::string valueDescription(const Description& option, OptionFront front) {
    if (!option.choices.empty()) {
        return nameList(option.choices);
    }
    if (front == OptionFront::CommandLine) {
        return option.valueName;
    }
    switch (option.form) {
        case OptionForm::Flag:
            return "bool";
        case OptionForm::WholeNumber:
            return "int";
        case OptionForm::Number:
            return "float";
        case OptionForm::Range:
            return option.valueName.ends_with("random") ? "float, (min, max) or \"random\""
                                                        : "float or (min, max)";
        case OptionForm::ImageSize:
            return "int or (width, height)";
        case OptionForm::ByteSize:
            return "int or str";
        case OptionForm::NumberList:
            return "sequence of floats";
        case OptionForm::Text:
            return option.name == "variant" ? "str or int" : "str";
    }
    return {};
}

// The default as Python writes it.
std::string pythonDefault(const Description& option) {
    switch (option.form) {
        case OptionForm::Flag:
            return (option.defaultValue == "true") != option.keywordNegated ? "True" : "False";
        case OptionForm::WholeNumber:
        case OptionForm::Number:
        case OptionForm::Range:
        case OptionForm::ImageSize:
            return option.defaultValue.empty() ? "None" : option.defaultValue;
        case OptionForm::NumberList:
            return option.defaultValue.empty() ? "None" : "[" + option.defaultValue + "]";
        case OptionForm::ByteSize:
        case OptionForm::Text:
            return option.defaultValue.empty() ? "None" : "\"" + option.defaultValue + "\"";
    }
    return "None";
}

}  // namespace

std::string BatchOptionDescription::pythonKeyword() const {
    if (!keyword.empty()) {
        return keyword;
    }
    std::string underscored = name;
    std::replace(underscored.begin(), underscored.end(), '-', '_');
    return underscored;
}

std::string BatchOptionDescription::shownName(OptionFront front) const {
    return front == OptionFront::CommandLine ? "--" + name : pythonKeyword();
}

std::span<const BatchOptionDescription> batchOptionDescriptions() {
    static const std::vector<Description> descriptions = describeOptions();
    return descriptions;
}

const BatchOptionDescription* findBatchOption(std::string_view name, OptionFront front) {
    for (const Description& option : batchOptionDescriptions()) {
        if (option.takenBy(front) &&
            (front == OptionFront::CommandLine ? option.name : option.pythonKeyword()) == name) {
            return &option;
        }
    }
    return nullptr;
}

std::vector<std::string> batchOptionNames(OptionFront front) {
    std::vector<std::string> names;
    for (const Description& option : batchOptionDescriptions()) {
        if (option.takenBy(front)) {
            names.push_back(option.shownName(front));
        }
    }
    return names;
}

namespace {

// `given` with the options of the preset it names (--preset) before them, less those that an
// option given replaces or excludes.
Result<std::vector<GivenOption>> withPreset(std::span<const GivenOption> given, OptionFront front) {
    std::vector<GivenOption> merged;
    const auto presetGiven = std::find_if(given.begin(), given.end(), [](const GivenOption& g) {
        return g.option->name == "preset";
    });
    if (presetGiven == given.end()) {
        merged.assign(given.begin(), given.end());
        return merged;
    }
    const BatchPreset* preset = findPreset(presetGiven->value);
    if (!preset) {
        const std::string nearest = nearestName(presetGiven->value, presetNames());
        return makeError(ErrorCode::InvalidArgument,
                         presetGiven->option->shownName(front) + " takes " +
                             nameList(presetNames()) + " (not '" + presetGiven->value + "'" +
                             (nearest.empty() ? "" : "; did you mean " + nearest + "?") +
                             "); list prints them with their sources.");
    }
    for (const PresetValue& value : preset->values) {
        const Description* option = findBatchOption(value.option, OptionFront::CommandLine);
        if (!option) {
            continue;  // BatchPresetsTest checks that every preset names real options.
        }
        // An option given explicitly replaces the preset's value, and drops the preset's
        // options that it excludes or that exclude it.
        const bool overridden =
            std::any_of(given.begin(), given.end(), [&](const GivenOption& entry) {
                if (entry.option == option) {
                    return true;
                }
                const auto& excludes = entry.option->excludes;
                return givenOn(entry) &&
                       (std::find(excludes.begin(), excludes.end(), option->name) !=
                            excludes.end() ||
                        std::find(option->excludes.begin(), option->excludes.end(),
                                  entry.option->name) != option->excludes.end());
            });
        if (!overridden) {
            merged.push_back({option, value.value});
        }
    }
    merged.insert(merged.end(), given.begin(), given.end());
    return merged;
}

}  // namespace

Result<void> applyBatchOptions(BatchOptions& options,
                               std::span<const GivenOption> explicitly,
                               OptionFront front) {
    ENCORE_TRY_ASSIGN(const std::vector<GivenOption> given, withPreset(explicitly, front));
    for (const GivenOption& entry : given) {
        if (!givenOn(entry)) {
            continue;
        }
        const Description& option = *entry.option;
        for (const std::string& excluded : option.excludes) {
            if (const GivenOption* other = findGiven(given, excluded)) {
                return makeError(ErrorCode::InvalidArgument, option.shownName(front) + " and " +
                                                                 other->option->shownName(front) +
                                                                 " exclude each other.");
            }
        }
        for (const std::string& needed : option.needs) {
            if (!findGiven(given, needed)) {
                return makeError(
                    ErrorCode::InvalidArgument,
                    option.shownName(front) + " requires " +
                        findBatchOption(needed, OptionFront::CommandLine)->shownName(front) + ".");
            }
        }
    }
    for (const Description& option : batchOptionDescriptions()) {
        for (const GivenOption& entry : given) {
            if (entry.option == &option) {
                ENCORE_TRY(option.apply(options, entry.value, option.shownName(front)));
            }
        }
    }
    return {};
}

std::string batchOptionsMarkdown() {
    std::string table =
        "| Command line | Python keyword | Value (default) | What it does |\n"
        "|---|---|---|---|\n";
    const auto escape = [](std::string text) {
        std::string escaped;
        for (char c : text) {
            if (c == '|') {
                escaped += "\\|";
            } else {
                escaped += c;
            }
        }
        return escaped;
    };
    for (const Description& option : batchOptionDescriptions()) {
        std::string commandLine = "-";
        if (option.commandLine) {
            commandLine = option.commandLineGlobal ? "`encore --" + option.name + " batch`"
                          : option.shortName ? "`-" + std::string(1, option.shortName) + "`, `--" +
                                                   option.name + "`"
                                             : "`--" + option.name + "`";
        }
        const std::string keyword =
            option.python ? "`" + option.pythonKeyword() + (option.keywordNegated ? "=False`" : "`")
                          : "-";
        std::string value = escape(valueDescription(option, OptionFront::CommandLine));
        if (!option.defaultValue.empty() && option.form != OptionForm::Flag) {
            value +=
                (value.empty() ? "" : " ") + std::string("(") + escape(option.defaultValue) + ")";
        }
        table += "| " + commandLine + " | " + keyword + " | " + (value.empty() ? "flag" : value) +
                 " | " + escape(option.help) + " |\n";
    }
    return table;
}

std::string batchOptionsDocstring() {
    std::string text;
    for (const Description& option : batchOptionDescriptions()) {
        if (!option.python) {
            continue;
        }
        text += option.pythonKeyword() + " (" + valueDescription(option, OptionFront::Python) +
                ", default " + pythonDefault(option) +
                "): " + (option.keywordNegated ? "False: " : "") + option.help;
        if (option.commandLine && !option.commandLineGlobal) {
            text += " (`--" + option.name + "`)";
        }
        text += ".\n";
    }
    return text;
}

}  // namespace encore::batch
