#pragma once

// A scripted viewer session (`encore view --script FILE`): what a user does, one step per line,
// run through the same input handling as real events. '#' starts a comment.
//
//   frames N                  render and present N frames (the animation clock advances
//                             1/60 s per frame in a script, so runs repeat exactly)
//   key NAME                  press and release a key: a letter, a digit, '[', ']', space,
//                             escape, left, right, up, down, plus, minus
//   drag left|right DX DY     drag the mouse with a button held, by DX, DY pixels
//   scroll DY                 turn the mouse wheel
//   resize W H                resize the window (waits until the window system applied it)
//   drop PATH                 drop a file on the window
//   screenshot PATH [overlay] save the next presented frame (without the overlay unless asked)
//   stats                     print the viewer's state as one line of key=value pairs
//   quit                      end the session (also at the end of the script)

#include <cstdint>
#include <string>
#include <vector>

#include "encore/core/Result.h"

namespace encore::view {

enum class ScriptCommand { Frames, Key, Drag, Scroll, Resize, Drop, Screenshot, Stats, Quit };

struct ScriptStep {
    ScriptCommand command = ScriptCommand::Frames;
    std::uint32_t count = 0;              // Frames
    int key = 0;                          // Key: a GLFW key code; Drag: a GLFW mouse button.
    double x = 0.0, y = 0.0;              // Drag: DX, DY; Scroll: 0, DY.
    std::uint32_t width = 0, height = 0;  // Resize
    std::string path;                     // Drop, Screenshot
    bool overlay = false;                 // Screenshot
    int line = 0;                         // Where it was written, for errors.
};

// Parses a script; errors name the file, the line and what is wrong.
Result<std::vector<ScriptStep>> parseViewScript(const std::string& text,
                                                const std::string& fileName);
Result<std::vector<ScriptStep>> loadViewScript(const std::string& path);

// The GLFW key code of a key name as scripts write it (0 if unknown).
int keyFromName(const std::string& name);

}  // namespace encore::view
