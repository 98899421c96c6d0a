#pragma once
// The viewer's tools, made in one place: the list the viewer loops over, and the two that
// scripted runs drive directly (the pick and the selection brush).
#include <functional>
#include <memory>
#include <vector>

#include "app/viewer/tool.h"

namespace trilab::viewer {

class PickTool;
class SelectionTool;
class SceneView;

struct Tools {
    std::vector<std::unique_ptr<Tool>> all;  ///< in the order they see the mouse
    PickTool* pick = nullptr;
    SelectionTool* selection = nullptr;
};

/// Every tool of the viewer over `context`, the selection overlay and the geodesic colours on
/// `scene`. Needs the GL context current (overlays).
Tools make_tools(ViewerContext& context, SceneView& scene);

}  // namespace trilab::viewer
