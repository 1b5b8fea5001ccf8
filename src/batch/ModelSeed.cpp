#include "batch/ModelSeed.h"

namespace encore::batch {
namespace {

// SplitMix64's finaliser (Steele, Lea and Flood 2014): nearby inputs give unrelated outputs.
std::uint64_t mix(std::uint64_t value) {
    value += 0x9e3779b97f4a7c15ULL;
    value = (value ^ (value >> 30)) * 0xbf58476d1ce4e5b9ULL;
    value = (value ^ (value >> 27)) * 0x94d049bb133111ebULL;
    return value ^ (value >> 31);
}

// FNV-1a, 64 bits: the same value on every platform (std::hash is not).
std::uint64_t hashName(std::string_view name) {
    std::uint64_t hash = 0xcbf29ce484222325ULL;
    for (const char c : name) {
        hash = (hash ^ std::uint8_t(c)) * 0x100000001b3ULL;
    }
    return hash;
}

}  // namespace

std::uint64_t modelSeed(std::uint64_t batchSeed, std::string_view modelName) {
    return modelName.empty() ? batchSeed : mix(batchSeed ^ mix(hashName(modelName)));
}

std::mt19937_64 randomStream(std::uint64_t modelSeed, RandomStream stream) {
    if (stream == RandomStream::Directions) {
        return std::mt19937_64(modelSeed);
    }
    return std::mt19937_64(mix(modelSeed ^ mix(std::uint64_t(stream))));
}

double unitInterval(std::mt19937_64& generator) {
    return double(generator() >> 11) * 0x1.0p-53;
}

}  // namespace encore::batch
