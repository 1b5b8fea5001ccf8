// The heads-up display: frame times, counters and state as text over a panel, a graph of the
// last frames' CPU and GPU times, the frozen culling frustum and a line of help.

#include <algorithm>
#include <filesystem>

#include "view/ViewerState.h"

namespace encore::view {
namespace {

constexpr OverlayColor kText{235, 235, 235, 255};
constexpr OverlayColor kDim{170, 170, 170, 255};
constexpr OverlayColor kError{255, 96, 96, 255};
constexpr OverlayColor kCpuColor{110, 220, 110, 255};
constexpr OverlayColor kGpuColor{255, 170, 60, 255};
constexpr OverlayColor kFrustumColor{255, 230, 60, 255};
constexpr OverlayColor kPanel{0, 0, 0, 150};

std::string fileName(const std::filesystem::path& path) {
    return path.filename().string();
}

}  // namespace

void Viewer::State::addFrustumLines(float) {
    if (!renderer || !renderer->cullingCamera()) {
        return;
    }
    const render::Camera& frozen = *renderer->cullingCamera();
    const glm::mat4 inverse = glm::inverse(frozen.viewProjection());
    // Far corners at a finite depth: the frozen camera's distance to the scene's far side.
    const glm::vec3 center = 0.5f * (scene->bounds.min + scene->bounds.max);
    const float reach =
        glm::length(center - frozen.position) + glm::length(scene->bounds.max - center);
    glm::vec3 corners[8];
    const glm::vec2 ndc[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int i = 0; i < 4; ++i) {
        auto unproject = [&](float depth) {
            const glm::vec4 point = inverse * glm::vec4(ndc[i], depth, 1.0f);
            return glm::vec3(point) / point.w;
        };
        const glm::vec3 nearPoint = unproject(0.0f);
        const glm::vec3 direction = glm::normalize(unproject(0.5f) - nearPoint);
        corners[i] = nearPoint;
        corners[i + 4] = frozen.position + direction * reach;
    }
    const glm::mat4 viewProjection = camera().viewProjection();
    auto toScreen = [&](const glm::vec3& point) -> std::optional<glm::vec2> {
        const glm::vec4 clip = viewProjection * glm::vec4(point, 1.0f);
        if (clip.w <= 1e-6f) {
            return std::nullopt;
        }
        const glm::vec2 ndcPoint = glm::vec2(clip) / clip.w;
        return glm::vec2((ndcPoint.x * 0.5f + 0.5f) * float(width),
                         (0.5f - ndcPoint.y * 0.5f) * float(height));
    };
    const int edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                              {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    for (const auto& edge : edges) {
        const auto from = toScreen(corners[edge[0]]);
        const auto to = toScreen(corners[edge[1]]);
        if (from && to) {
            overlay->addLine(*from, *to, 2.0f, kFrustumColor);
        }
    }
}

void Viewer::State::buildOverlay() {
    overlay->clear();
    addFrustumLines(0.0f);
    std::vector<std::pair<std::string, OverlayColor>> lines;
    double fps = 0.0;
    if (!frameIntervals.empty()) {
        double sum = 0.0;
        for (double interval : frameIntervals) {
            sum += interval;
        }
        fps = sum > 0.0 ? double(frameIntervals.size()) / sum : 0.0;
    }
    lines.push_back(
        {format("%.1f fps (%.2f ms)  %ux%u  present %s", fps, fps > 0.0 ? 1000.0 / fps : 0.0, width,
                height, presentModeName(surface->presentMode())),
         kText});
    lines.push_back({"strategy " + strategyLabel(), kText});
    std::string gpu = lastFrame.gpuMilliseconds ? format("%.3f ms", *lastFrame.gpuMilliseconds)
                                                : std::string("n/a (no timestamp queries)");
    lines.push_back({format("CPU encode %.3f ms  submit %.3f ms", lastFrame.encodeMilliseconds,
                            lastFrame.submitMilliseconds),
                     kCpuColor});
    lines.push_back({"GPU " + gpu, kGpuColor});
    const std::uint64_t bundlesRecorded = renderer ? renderer->stats().bundlesRecorded
                                          : animometer && options.animometer->bundle ? 1
                                                                                     : 0;
    lines.push_back({format("draws %llu  executeBundles %llu  draws in bundles %llu",
                            (unsigned long long)lastFrame.counters.drawCalls(),
                            (unsigned long long)lastFrame.counters.executeBundles,
                            (unsigned long long)lastFrame.bundleContents.drawCalls()),
                     kText});
    lines.push_back({format("bundles recorded %llu", (unsigned long long)bundlesRecorded), kText});
    if (scene) {
        std::string animation;
        if (!scene->animations.empty()) {
            animation = animationIndex < 0 ? "  animation: all"
                                           : "  animation " + std::to_string(animationIndex);
            animation += paused ? " (paused)" : "";
        }
        lines.push_back({fileName(scene->sourcePath) + animation, kDim});
    }
    if (frozenCulling) {
        lines.push_back({"culling frustum frozen (C)", kFrustumColor});
    }
    lines.push_back({context->adapterDescription().summary(), kDim});
    if (!message.empty()) {
        lines.push_back({message, messageIsError ? kError : kDim});
    }

    constexpr float kScale = 2.0f;
    constexpr float kMargin = 8.0f;
    constexpr float kLineHeight = 9.0f * kScale;
    float panelWidth = 0.0f;
    for (const auto& [text, color] : lines) {
        panelWidth = std::max(panelWidth, Overlay::measureText(text, kScale).x);
    }
    const float graphHeight = 48.0f;
    panelWidth =
        std::min(std::max(panelWidth, 2.0f * kHistoryFrames) + 2.0f * kMargin, float(width));
    const float panelHeight = float(lines.size()) * kLineHeight + graphHeight + 3.0f * kMargin;
    overlay->addRectangle(0.0f, 0.0f, panelWidth, panelHeight, kPanel);
    float y = kMargin;
    for (const auto& [text, color] : lines) {
        overlay->addText(kMargin, y, text, color, kScale);
        y += kLineHeight;
    }
    // The last seconds of CPU and GPU time, each frame a bar, on one scale.
    y += kMargin;
    double highest = 1.0;
    for (const FrameSample& frame : history) {
        highest = std::max({highest, frame.cpuMilliseconds, frame.gpuMilliseconds.value_or(0.0)});
    }
    float x = kMargin;
    for (const FrameSample& frame : history) {
        const float cpu = float(frame.cpuMilliseconds / highest) * graphHeight;
        overlay->addRectangle(x, y + graphHeight - cpu, 1.0f, cpu, kCpuColor);
        if (frame.gpuMilliseconds) {
            const float gpuHeight = float(*frame.gpuMilliseconds / highest) * graphHeight;
            overlay->addRectangle(x + 1.0f, y + graphHeight - gpuHeight, 1.0f, gpuHeight,
                                  kGpuColor);
        }
        x += 2.0f;
    }
    overlay->addText(kMargin + 2.0f * kHistoryFrames + 4.0f, y, format("%.1f ms", highest), kDim,
                     1.5f);

    const std::string help =
        "drag orbit  right-drag pan  wheel zoom  F frame  1-8 strategy  B bundle  C freeze "
        "culling  space pause  [ ] animation  S screenshot  O overlay";
    const float helpHeight = 9.0f * 1.5f;
    overlay->addRectangle(0.0f, float(height) - helpHeight - 6.0f, float(width), helpHeight + 6.0f,
                          kPanel);
    overlay->addText(kMargin, float(height) - helpHeight - 2.0f, help, kDim, 1.5f);
}

}  // namespace encore::view
