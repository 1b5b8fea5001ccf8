#pragma once

// The random numbers of a batch: every draw for a model (its random view directions, their
// jitter, distances and fields of view, its environment, rotation and intensity) comes from the
// batch's seed and the model's output name, never from the order in which models are rendered,
// so a resumed, re-ordered or distributed run draws the same for every model, on every machine.
// Each kind of draw has a stream of its own: asking for one more (a jitter) leaves the others as
// they were.

#include <cstdint>
#include <random>
#include <string_view>

namespace encore::batch {

// The seed of a model's streams; `batchSeed` itself for an empty name (the view rig of
// Renderer.render_views, which has no model name).
std::uint64_t modelSeed(std::uint64_t batchSeed, std::string_view modelName);

enum class RandomStream : std::uint64_t {
    Directions,  // The generator seeded with the model seed itself, as --random-views always was.
    Jitter,
    Distance,
    FieldOfView,
    Lighting,
    Elevation,   // An orbit's elevation drawn from a range.
    PointCloud,  // The surface points of --point-cloud.
};

std::mt19937_64 randomStream(std::uint64_t modelSeed, RandomStream stream);

// A double in [0, 1) from the generator's raw bits: std::uniform_real_distribution may differ
// between standard libraries, and a seed promises the same draws everywhere.
double unitInterval(std::mt19937_64& generator);

}  // namespace encore::batch
