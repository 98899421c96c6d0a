#pragma once
// The viewer's tools, made in one place: the list the viewer loops over (its order is the
// sidebar's), and the ones scripted runs drive directly (the pick, the selection brush, the
// level of detail, the decomposition).
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "app/viewer/tool.h"

namespace trilab::viewer {

class DecimationTool;
class FrequencyTool;
class PickTool;
class SelectionTool;

struct Tools {
    /// In the sidebar's order; they see the mouse in this order too (the selection takes
    /// Ctrl/Alt drags before a click picks).
    std::vector<std::unique_ptr<Tool>> all;
    PickTool* pick = nullptr;
    SelectionTool* selection = nullptr;
    DecimationTool* decimation = nullptr;
    FrequencyTool* frequency = nullptr;
    /// The tools as the menus, --panels, key bindings and saved settings take them.
    ToolList list() const;
    /// Every tool's panel entries, in order.
    PanelEntries entries() const;
};

/// Every tool of the viewer over `context`. `exact`: the surface the selection overlay is
/// uploaded to, `geodesic_colored`: the picks version the geodesic colours on the screen show
/// (nullptr and an empty function in the panel tests, which draw no view). The generic
/// operation tool holds every registered operation that no other tool's panel holds.
Tools make_tools(ViewerContext& context, MeshRenderer* exact,
                 std::function<std::uint64_t()> geodesic_colored);

}  // namespace trilab::viewer
