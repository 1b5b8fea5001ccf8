#include <array>
#include <cstdio>
#include <memory>
#include <string>

#include "Commands.h"
#include "core/FileIO.h"
#include "encore/image/ImageCodec.h"
#include "image/ImageCompare.h"

namespace encore::app {

namespace {

// The difference image's gain: small rendering differences (a few levels) become visible.
constexpr float kDifferenceGain = 4.0f;

struct CompareOptions {
    std::string first;
    std::string second;
    std::string sideBySidePath;
    bool json = false;
};

std::string sizeText(const image::ImageRgba8& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
}

// Every failure names the file first ("error: <file>: ..."), like the glTF loader's messages.
Result<image::ImageRgba8> readNamedImage(const std::string& path) {
    auto bytes = readFile(path);
    if (!bytes) {
        return bytes.error().withContext(path);
    }
    auto decoded = image::decodeImage(*bytes);
    if (!decoded) {
        return decoded.error().withContext(path);
    }
    return decoded;
}

int runCompare(const CompareOptions& options) {
    auto first = readNamedImage(options.first);
    if (!first) {
        return reportError(first.error());
    }
    auto second = readNamedImage(options.second);
    if (!second) {
        return reportError(second.error());
    }
    if (first->width != second->width || first->height != second->height) {
        // Bad input rather than a usage error: exit code 1.
        return reportError(makeError(ErrorCode::InvalidFormat,
                                     options.second + ": its size (" + sizeText(*second) +
                                         ") differs from that of " + options.first + " (" +
                                         sizeText(*first) + ")."));
    }
    auto ssim = image::ssimLuminance(*first, *second);
    if (!ssim) {
        return reportError(ssim.error().withContext(options.second));
    }
    auto error = image::colorError(*first, *second);
    if (!error) {
        return reportError(error.error().withContext(options.second));
    }
    if (!options.sideBySidePath.empty()) {
        const std::array<image::ImageRgba8, 3> panels = {
            *first, *second, image::differenceImage(*first, *second, kDifferenceGain)};
        if (auto written = image::writePng(options.sideBySidePath, image::sideBySide(panels));
            !written) {
            return reportError(written.error());
        }
    }
    if (options.json) {
        nlohmann::json report = {{"a", options.first},
                                 {"b", options.second},
                                 {"width", first->width},
                                 {"height", first->height},
                                 {"ssim", *ssim},
                                 {"colorError",
                                  {{"meanAbsolute", error->meanAbsolute},
                                   {"maxAbsolute", error->maxAbsolute},
                                   {"threshold", image::kColorErrorThreshold},
                                   {"fractionOverThreshold", error->fractionOverThreshold}}}};
        if (!options.sideBySidePath.empty()) {
            report["sideBySide"] = options.sideBySidePath;
        }
        std::printf("%s\n", report.dump(2).c_str());
    } else {
        std::printf("size: %s\n", sizeText(*first).c_str());
        std::printf("ssim: %.6f\n", *ssim);
        std::printf("mean absolute error: %.4f (0..255)\n", error->meanAbsolute);
        std::printf("max absolute error: %d\n", error->maxAbsolute);
        std::printf("pixels differing by more than %d: %.4f%%\n", image::kColorErrorThreshold,
                    error->fractionOverThreshold * 100.0);
    }
    if (!options.sideBySidePath.empty()) {
        std::fprintf(stderr, "side-by-side: %s\n", options.sideBySidePath.c_str());
    }
    return kExitOk;
}

}  // namespace

void addCompareCommand(CLI::App& app, const GlobalOptions&, int& exitCode) {
    auto options = std::make_shared<CompareOptions>();
    auto* command = app.add_subcommand(
        "compare",
        "Compare two images of the same size: SSIM of their luma (11x11 Gaussian window) and "
        "the colour error per pixel.");
    command->add_option("a", options->first, "The first image (PNG or JPEG)")->required();
    command->add_option("b", options->second, "The second image (PNG or JPEG)")->required();
    command->add_option("-o,--output", options->sideBySidePath,
                        "Write A | B | difference (x4) side by side to this PNG");
    command->add_flag("--json", options->json, "Print JSON instead of text");
    command->callback([options, &exitCode] { exitCode = runCompare(*options); });
}

}  // namespace encore::app
