#pragma once
// `trilab-cli record`: the command line of the recorder (app/record/recorder.h), which runs
// one operation on a mesh and renders the morph from the mesh before it to the mesh after it
// offscreen, as numbered PNG frames (and, when ffmpeg is on the PATH and --mp4 is given, an
// H.264 MP4). See `trilab-cli record --help`.
//
// This header needs no GL: trilab-cli includes it whether or not the renderer is built.
#include <string>
#include <vector>

namespace trilab::cli {

/// Runs `trilab-cli record ARGS...` (the arguments after the command name). Returns the
/// exit code; throws trilab::Error for bad arguments or files.
int run_record_command(const std::vector<std::string>& args);

}  // namespace trilab::cli
