// What the session's owners share; see session_core.h.
#include "app/session/session_core.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <utility>

namespace trilab::viewer {
namespace {

using Clock = std::chrono::steady_clock;
const Clock::time_point kEpoch = Clock::now();

}  // namespace

bool is_session_path(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".trilab" || ext == ".journal";
}

double SessionCore::now() const {
    return std::chrono::duration<double>(Clock::now() - kEpoch).count();
}

void SessionCore::notify_error(const std::string& text) {
    log.error(text);
    notice = Notice{Notice::Level::Error, text, {}, true};
}

void SessionCore::inform(const std::string& text) {
    notice = Notice{Notice::Level::Info, text, {}, false};
}

void SessionCore::busy_error() {
    notify_error("busy: wait for \"" + jobs.name() + "\" or cancel it");
}

void SessionCore::log_history_messages(const std::vector<std::string>& messages) {
    for (const std::string& m : messages) log.warning(m);
}

void SessionCore::push_entry(const std::string& label, const std::string& parameters, double ms,
                             std::vector<HalfedgeMesh> meshes,
                             std::vector<MorphCorrespondence> correspondences,
                             const Operation& op) {
    log_history_messages(document.history.push(label, parameters, ms, std::move(meshes),
                                               std::move(correspondences), op));
    if (state_changed) state_changed(false);
}

void SessionCore::show(Shown::Kind kind, const HalfedgeMesh* mesh, LevelOfDetail* level) {
    shown.kind = kind;
    shown.mesh = mesh;
    shown.positions.clear();
    shown.level = level;
    bump();
}

void SessionCore::show_document() {
    show(Shown::Kind::Document, &document.mesh());
    if (document_shown) document_shown();
}

}  // namespace trilab::viewer
