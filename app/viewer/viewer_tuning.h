#pragma once
// Constants the viewer's files share (viewer*.cpp); not part of any interface.
#include <cstddef>

namespace trilab::viewer::tuning {

inline constexpr const char* kTitle = "trilab";
/// ImGui settles hover and popups within a few frames.
inline constexpr int kFramesAfterInput = 4;
inline constexpr std::size_t kColoringJobFaces = 200000;  ///< larger meshes colour in a job
/// The automatic wireframe overlay is on while a typical edge is at least this many line
/// widths long on the screen, and goes off below the second figure (no flicker at the edge).
inline constexpr double kWireOnLineWidths = 10.0, kWireOffLineWidths = 8.0;
/// A left press and release closer than this (window pixels) is a click: it picks, and the
/// view does not turn until the cursor has moved further.
inline constexpr float kClickSlopPixels = 3.0f;
/// Scripted runs wait at most this many extra frames for jobs and morphs to end.
inline constexpr int kMaxSettleFrames = 1000;

}  // namespace trilab::viewer::tuning
