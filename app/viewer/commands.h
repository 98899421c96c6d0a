#pragma once
// What panels ask the viewer to do. Panels never touch the document, the window or the GPU:
// they queue commands, and the viewer executes them in one place after the UI is drawn.
#include <string>
#include <variant>
#include <vector>

namespace trilab::viewer {

struct LoadFile {
    std::string path;
};
struct SaveFile {
    std::string path;
};
struct RevertFile {};
struct LoadTexture {
    std::string path;
};
struct FitView {};
/// Recompute the vertex colouring (its kind or options changed).
struct UpdateColoring {};
/// Compute texture coordinates by the chosen projection (the mesh has none).
struct ProjectTexCoords {};
/// A PNG of the scene without the panels.
struct TakeScreenshot {
    std::string path;
    int width = 0, height = 0;
    bool transparent = false;
};
struct PrintInfo {};
struct CancelJob {};
struct Quit {};

using Command = std::variant<LoadFile, SaveFile, RevertFile, LoadTexture, FitView, UpdateColoring,
                             ProjectTexCoords, TakeScreenshot, PrintInfo, CancelJob, Quit>;
using CommandQueue = std::vector<Command>;

}  // namespace trilab::viewer
