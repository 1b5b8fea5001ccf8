#include "BatchPassOptions.h"

#include "batch/OptionNames.h"

namespace encore::app {

void addBatchPassOptions(CLI::App& command, BatchPassOptions& options, CLI::Option* depth) {
    command.add_flag("--albedo", options.albedo,
                     "Also write the base colour per view (000_albedo.png: texture x factor x "
                     "vertex colour, sRGB)");
    command.add_flag("--material", options.material,
                     "Also write occlusion, roughness and metallic per view (000_material.png, "
                     "linear R, G, B)");
    auto* segmentation = command.add_flag(
        "--segmentation", options.segmentation,
        "Also write 16-bit ids per view (000_segmentation.png: 0 background, else 1 + the node "
        "index; names in transforms.json); needs --samples 1");
    command
        .add_option("--segmentation-by", options.segmentationBy,
                    "What a segmentation id counts: node, mesh or material")
        ->check(CLI::IsMember(batch::namesOf(batch::segmentationByNames())))
        ->needs(segmentation)
        ->capture_default_str();
    command
        .add_option("--depth-format", options.depthFormat,
                    "png: 16-bit steps of depth_scale; exr: 32-bit float distances along the "
                    "camera axis, infinity where empty (000_depth.exr)")
        ->check(CLI::IsMember(batch::namesOf(batch::depthFormatNames())))
        ->needs(depth)
        ->capture_default_str();
    command.add_flag("--hdr", options.hdr,
                     "Also write the linear colour before exposure and tone mapping per view "
                     "(000_hdr.exr, half float, premultiplied alpha)");
    command.add_flag("--pass-frames", options.passFrames,
                     "Draw each pass as one more frame through a debug channel instead of in the "
                     "colour frame's render pass (the same images, slower: for comparisons)");
}

void applyBatchPassOptions(const BatchPassOptions& options, batch::ExtraImages& images) {
    images.albedo = options.albedo;
    images.material = options.material;
    images.segmentation = options.segmentation;
    images.hdr = options.hdr;
    images.drawing = options.passFrames ? batch::PassDrawing::Frames : batch::PassDrawing::Targets;
    // The names were checked by the parser (CLI::IsMember over the same tables).
    images.segmentationBy =
        *batch::valueNamed(batch::segmentationByNames(), options.segmentationBy);
    images.depthFormat = *batch::valueNamed(batch::depthFormatNames(), options.depthFormat);
}

}  // namespace encore::app
