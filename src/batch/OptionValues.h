#pragma once

// The forms the batch's options take as text, parsed once for every front (the command line's
// values, Python's keywords turned into text): each error names the option as its front spells
// it (`shown`: "--views", "views") and says what it takes.

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "encore/batch/ViewRig.h"
#include "encore/core/Result.h"
#include "encore/render/RendererOptions.h"

namespace encore::batch {

// "true" or "false" (what a flag's front gives).
Result<bool> parseFlag(std::string_view text, std::string_view shown);

// A whole number in [min, max].
Result<std::uint64_t> parseWholeNumber(std::string_view text,
                                       std::string_view shown,
                                       std::uint64_t min,
                                       std::uint64_t max);

// A finite number in [min, max].
Result<float> parseNumber(std::string_view text, std::string_view shown, float min, float max);

// "X" or "MIN:MAX", each a finite number.
Result<ValueRange> parseRange(std::string_view text, std::string_view shown);

// "A,B,...": finite numbers separated by commas, at least one and at most `maxCount`.
Result<std::vector<float>> parseNumberList(std::string_view text,
                                           std::string_view shown,
                                           std::size_t maxCount);

// "W" or "WxH" in pixels, each from 1 to 8192.
Result<std::pair<std::uint32_t, std::uint32_t>> parseImageSize(std::string_view text,
                                                               std::string_view shown);

// Bytes: 1000000, 500MB, 1GiB, ... (at least 1).
Result<std::uint64_t> parseByteSize(std::string_view text, std::string_view shown);

// "transparent" (alpha 0), "env" (the environment drawn) or a colour written #rrggbb (sRGB),
// set into `options`.
Result<void> parseBackground(std::string_view text,
                             std::string_view shown,
                             render::ToneMappingOptions& options);

// The name in `names` closest to `name` by edit distance, when it is close enough to be a
// plausible typo (two edits, or a third of its letters); empty otherwise.
std::string nearestName(std::string_view name, const std::vector<std::string>& names);

}  // namespace encore::batch
