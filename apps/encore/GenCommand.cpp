#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include "Commands.h"
#include "core/FileIO.h"
#include "scene/CrowdGenerator.h"
#include "scene/SceneGenerator.h"

namespace encore::app {

namespace {
struct GenOptions {
    scene::GeneratorOptions generator;
    std::string output = "scene.glb";
    std::uint32_t crowd = 0;  // --crowd N: an animated crowd instead.
};
}  // namespace

void addGenCommand(CLI::App& app, const GlobalOptions&, int& exitCode) {
    auto options = std::make_shared<GenOptions>();
    auto* command = app.add_subcommand(
        "gen", "Generate a glTF scene (.glb): distinct meshes, shared materials, many objects.");
    command->add_option("--objects", options->generator.objectCount, "Number of objects (nodes)")
        ->capture_default_str();
    command->add_option("--meshes", options->generator.meshCount, "Number of distinct meshes")
        ->capture_default_str();
    command
        ->add_option("--materials", options->generator.materialCount, "Number of shared materials")
        ->capture_default_str();
    command
        ->add_option("--layout", options->generator.layout,
                     "Where the objects stand: grid (one flat square grid), lattice (a wide box "
                     "of layers to fly through) or city (buildings on a street grid)")
        ->transform(CLI::CheckedTransformer(
            std::map<std::string, scene::SceneLayout>{{"grid", scene::SceneLayout::Grid},
                                                      {"lattice", scene::SceneLayout::Lattice},
                                                      {"city", scene::SceneLayout::City}},
            CLI::ignore_case));
    command->add_option("--seed", options->generator.seed, "Random seed for object placement")
        ->capture_default_str();
    command
        ->add_option("--tessellation", options->generator.tessellation,
                     "Segments around the round shapes (3 to 256)")
        ->capture_default_str();
    options->generator.textures = true;
    command->add_flag("--textures,!--no-textures", options->generator.textures,
                      "Give every other material a base colour and a metallic-roughness texture "
                      "(default: on)");
    command->add_option("--crowd", options->crowd,
                        "Generate an animated crowd of N skinned characters instead, each "
                        "playing the animation with its own time offset");
    command->add_option("-o,--output", options->output, "The .glb file to write")
        ->capture_default_str();
    command->callback([options, &exitCode] {
        auto glb = options->crowd > 0 ? scene::generateCrowdGlb({options->crowd})
                                      : scene::generateSceneGlb(options->generator);
        if (!glb) {
            exitCode = reportError(glb.error());
            return;
        }
        if (auto written = writeFile(options->output, *glb); !written) {
            exitCode = reportError(written.error());
            return;
        }
        std::printf("%s\n", options->output.c_str());
        exitCode = kExitOk;
    });
}

}  // namespace encore::app
