#pragma once
// Encoding numbered PNG frames into an H.264 MP4 with ffmpeg, shared by `trilab-cli record
// --mp4` (recorder.h) and the viewer's Record section. ffmpeg runs through posix_spawn with an
// argument vector, never through a shell: a folder or name with quotes, `$(...)`, backticks or
// spaces is one argument as it is, and nothing in it is ever run.
#include <string>
#include <vector>

namespace trilab::record {

/// What to encode: folder/name_0000.png ... (frame numbers zero-padded to `digits`, as
/// frame_file_name() writes them) into folder/name.mp4.
struct Mp4Request {
    std::string folder;
    std::string name;  ///< the frames' base name (no '/'); a '%' is escaped for ffmpeg
    int frames = 0;
    int fps = 30;
    int digits = 4;
};

/// The ffmpeg argument vector (argv[0] is `ffmpeg`, the program's path) that encodes
/// `request` into `output` (a partial file renamed when complete). Pure: for tests.
std::vector<std::string> mp4_encoder_arguments(const std::string& ffmpeg, const Mp4Request& request,
                                               const std::string& output);

/// Runs `argv` (argv[0] a path; no shell) with stdin from /dev/null and stdout and stderr
/// into the file `log`. Returns the exit status, or -1 with `error` set when it did not start
/// or did not exit normally.
int run_program(const std::vector<std::string>& argv, const std::string& log, std::string& error);

/// Encodes `request` into folder/name.mp4 with the ffmpeg found on $PATH (through a partial
/// file, renamed when ffmpeg succeeded). Returns the MP4's path, or "" with `note` saying why
/// there is none (no ffmpeg, its exit status and last message); never throws for a failed
/// encoding.
std::string encode_mp4(const Mp4Request& request, std::string& note);

}  // namespace trilab::record
