// The script driver: runs a ViewScript's steps through the same input handling and frame loop
// as a user's session, and prints the `stats` lines that tests compare.

#include <algorithm>
#include <chrono>
#include <optional>
#include <thread>

#include "view/ViewerState.h"

namespace encore::view {
namespace {

// A script's animation clock advances by a fixed step per frame, so that runs repeat exactly.
constexpr double kScriptFrameSeconds = 1.0 / 60.0;

}  // namespace

std::string Viewer::State::statsLine() const {
    std::string label = strategyLabel();
    std::replace(label.begin(), label.end(), ' ', '_');
    std::string line = "stats strategy=" + label;
    const std::optional<render::RendererStats> stats =
        renderer ? std::optional(renderer->stats()) : std::nullopt;
    const std::uint64_t bundlesRecorded = stats ? stats->bundlesRecorded
                                          : animometer && options.animometer->bundle ? 1
                                                                                     : 0;
    line += format(
        " bundled=%d size=%ux%u frames=%llu bundlesRecorded=%llu draws=%llu "
        "executeBundles=%llu",
        renderer ? int(renderer->bundled()) : int(options.animometer->bundle), width, height,
        (unsigned long long)frameNumber, (unsigned long long)bundlesRecorded,
        (unsigned long long)lastFrame.counters.drawCalls(),
        (unsigned long long)lastFrame.counters.executeBundles);
    if (renderer) {
        // GPU scenes built and bytes uploaded since the viewer opened: a switch of strategy
        // changes neither.
        line +=
            format(" sceneUploads=%llu uploadedBytes=%llu", (unsigned long long)stats->sceneUploads,
                   (unsigned long long)stats->uploadedBytes);
        // The material variant drawn (KHR_materials_variants): its index, or "default".
        line += " variant=" +
                (variantIndex < 0 ? std::string("default") : std::to_string(variantIndex));
    }
    if (scene) {
        line += " scene=" + scene->sourcePath.string();
    }
    line += std::string(" cullingFrozen=") + (frozenCulling ? "1" : "0");
    if (!message.empty() && messageIsError) {
        line += " error=" + message;
    }
    return line;
}

Result<void> Viewer::State::runScriptStep(const ScriptStep& step) {
    auto pressRelease = [&](int key) -> Result<void> {
        InputEvent press;
        press.kind = InputKind::Key;
        press.key = key;
        press.pressed = true;
        ENCORE_TRY(handle(press));
        press.pressed = false;
        return handle(press);
    };
    switch (step.command) {
        case ScriptCommand::Frames:
            for (std::uint32_t i = 0; i < step.count && !quit; ++i) {
                for (const InputEvent& event : window->pollEvents()) {
                    ENCORE_TRY(handle(event));
                }
                ENCORE_TRY(renderFrame(kScriptFrameSeconds));
            }
            return {};
        case ScriptCommand::Key:
            return pressRelease(step.key);
        case ScriptCommand::Drag: {
            InputEvent event;
            event.kind = InputKind::CursorMove;
            event.x = cursorX;
            event.y = cursorY;
            ENCORE_TRY(handle(event));
            InputEvent button;
            button.kind = InputKind::MouseButton;
            button.key = step.key;
            button.pressed = true;
            ENCORE_TRY(handle(button));
            event.x += step.x;
            event.y += step.y;
            ENCORE_TRY(handle(event));
            button.pressed = false;
            return handle(button);
        }
        case ScriptCommand::Scroll: {
            InputEvent event;
            event.kind = InputKind::Scroll;
            event.y = step.y;
            return handle(event);
        }
        case ScriptCommand::Resize: {
            window->setSize(step.width, step.height);
            // The window system applies the size asynchronously; wait for its event.
            const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
            while (std::chrono::steady_clock::now() < deadline) {
                for (const InputEvent& event : window->pollEvents()) {
                    ENCORE_TRY(handle(event));
                }
                if (width == step.width && height == step.height) {
                    return {};
                }
                std::this_thread::sleep_for(std::chrono::milliseconds(5));
            }
            return makeError(ErrorCode::DeviceError,
                             format("script line %d: the window system did not resize the window "
                                    "to %ux%u (it is %ux%u).",
                                    step.line, step.width, step.height, width, height));
        }
        case ScriptCommand::Drop: {
            InputEvent event;
            event.kind = InputKind::Drop;
            event.paths = {step.path};
            return handle(event);
        }
        case ScriptCommand::Screenshot:
            screenshots.push_back({step.path, step.overlay});
            // Saved with the next frame, as the window shows it.
            return renderFrame(kScriptFrameSeconds);
        case ScriptCommand::Stats:
            if (options.report) {
                options.report(statsLine());
            }
            return {};
        case ScriptCommand::Quit:
            quit = true;
            return {};
    }
    return {};
}

}  // namespace encore::view
