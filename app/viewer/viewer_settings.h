#pragma once
// The viewer's settings as the key=value text a session file and the crash journal store
// (SessionExtras::viewer_settings, docs/file-formats.md#session-files): the camera, the
// render style, the colouring (with the legend's percentile range), the texture choice, every
// operation panel's typed operation (Operation::text()) and the other panels' parameters
// (frequency band, morph, record, screenshot, level of detail). Numbers are written with
// enough digits to read back bit for bit (%.9g for float, %.17g for double).
#include <string>
#include <vector>

#include "app/session/session.h"
#include "app/viewer/panels.h"
#include "render/camera.h"
#include "render/mesh_renderer.h"

namespace trilab::viewer {

/// What the settings text covers, by reference.
struct ViewerSettingsRefs {
    Camera& camera;
    RenderStyle& style;
    ViewSettings& settings;
    PanelState& panels;
    MorphState& morph;      ///< a copy of the session's (SetMorphAnimation applies it)
    const ToolList& tools;  ///< each writes and reads its own (Tool::settings())
};

/// One "key=value" line per setting ('\' and newlines in values escaped as \\ and \n).
std::string viewer_settings_text(const ViewerSettingsRefs& refs);

/// Applies `text` (as viewer_settings_text() writes it). A line that cannot be applied (an
/// unknown key, a bad value, an operation that does not parse) leaves that setting as it is
/// and adds a note naming its line, key and reason; never throws for bad text.
std::vector<std::string> apply_viewer_settings(const std::string& text,
                                               const ViewerSettingsRefs& refs);

}  // namespace trilab::viewer
