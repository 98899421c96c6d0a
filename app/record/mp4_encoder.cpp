// ffmpeg through posix_spawn with an argument vector; see mp4_encoder.h.
#include "app/record/mp4_encoder.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "app/record/recorder.h"

extern char** environ;

namespace trilab::record {
namespace {

namespace fs = std::filesystem;

/// The last non-empty line of a text file (at most 300 characters), or "".
std::string last_line(const std::string& path) {
    std::ifstream in(path);
    std::string line, last;
    while (std::getline(in, line))
        if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
    if (last.size() > 300) last = last.substr(0, 300) + "...";
    return last;
}

}  // namespace

std::vector<std::string> mp4_encoder_arguments(const std::string& ffmpeg, const Mp4Request& request,
                                               const std::string& output) {
    // ffmpeg's image2 pattern: a literal '%' in the name is written "%%".
    std::string escaped;
    for (char ch : request.name) escaped += ch == '%' ? std::string("%%") : std::string(1, ch);
    const std::string pattern =
        (fs::path(request.folder) / (escaped + "_%0" + std::to_string(request.digits) + "d.png"))
            .string();
    return {ffmpeg,
            "-nostdin",
            "-hide_banner",
            "-loglevel",
            "error",
            "-y",
            "-framerate",
            std::to_string(request.fps),
            "-start_number",
            "0",
            "-i",
            pattern,
            "-frames:v",
            std::to_string(request.frames),
            "-vf",
            "pad=ceil(iw/2)*2:ceil(ih/2)*2",
            "-c:v",
            "libx264",
            "-pix_fmt",
            "yuv420p",
            "-movflags",
            "+faststart",
            "-f",
            "mp4",
            output};
}

int run_program(const std::vector<std::string>& argv, const std::string& log, std::string& error) {
    if (argv.empty()) {
        error = "no program to run";
        return -1;
    }
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) {
        error = std::string("cannot start ") + argv[0] + ": " + std::strerror(rc);
        return -1;
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) {
            error = std::string("waiting for ") + argv[0] + ": " + std::strerror(errno);
            return -1;
        }
    }
    if (WIFEXITED(status)) return WEXITSTATUS(status);
    error = argv[0] + std::string(" was stopped by signal ") +
            std::to_string(WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    return -1;
}

std::string encode_mp4(const Mp4Request& request, std::string& note) {
    const std::string ffmpeg = find_on_path("ffmpeg");
    if (ffmpeg.empty()) {
        note = "ffmpeg is not on the PATH, so no MP4 was written (the PNG frames are complete)";
        return "";
    }
    const fs::path dir(request.folder);
    const std::string target = (dir / (request.name + ".mp4")).string();
    const std::string partial = (dir / ("." + request.name + ".mp4.part")).string();
    const std::string log = (fs::temp_directory_path() /
                             ("trilab-record-ffmpeg-" + std::to_string(::getpid()) + ".log"))
                                .string();
    std::string error;
    const int status = run_program(mp4_encoder_arguments(ffmpeg, request, partial), log, error);
    std::error_code ec;
    if (status == 0) {
        fs::rename(partial, target, ec);
        if (!ec) {
            fs::remove(log, ec);
            return target;
        }
        error = "cannot rename " + partial + " to " + target + ": " + ec.message();
    } else if (status > 0) {
        error = "ffmpeg failed (exit status " + std::to_string(status) + ")";
        const std::string why = last_line(log);
        if (!why.empty()) error += ": " + why;
    }
    fs::remove(partial, ec);
    fs::remove(log, ec);
    note = error + "; no MP4 was written (the PNG frames are complete)";
    return "";
}

}  // namespace trilab::record
