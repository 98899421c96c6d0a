// Sessions and the crash journal in the window: what a session stores beside the history (the
// view, the panels, the texture), the recovery question at start-up, and --save-session.
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <utility>

#include "app/viewer/viewer.h"
#include "app/viewer/viewer_settings.h"
#include "core/io/file_util.h"

namespace trilab::viewer {

SessionExtras Viewer::session_extras() const {
    // The settings functions take references for both directions; writing only reads them.
    ViewerContext& self = const_cast<ViewerContext&>(context_);
    MorphState morph = context_.session.morph();
    SessionExtras extras;
    extras.viewer_settings = viewer_settings_text(
        {self.view.camera, self.view.style, self.view.settings, self.panels, morph, tools_.list()});
    extras.texture_path = scene_->texture_path();
    return extras;
}

void Viewer::apply_session_extras(const SessionExtras& extras) {
    ViewState& view = context_.view;
    Session& session = context_.session;
    MorphState morph = session.morph();
    for (const std::string& note : apply_viewer_settings(
             extras.viewer_settings,
             {view.camera, view.style, view.settings, context_.panels, morph, tools_.list()}))
        session.log().warning(note);
    session.execute(SetMorphAnimation{morph.duration, morph.easing, morph.playback});
    view.fitted = false;                                       // the stored camera stays on resize
    const bool checkerboard = view.settings.use_checkerboard;  // as the session stored it
    if (!extras.texture_path.empty()) {
        try {
            scene_->set_texture_image(
                extras.texture_bytes.empty()
                    ? read_image(extras.texture_path)
                    : read_image_bytes(extras.texture_bytes, extras.texture_path),
                extras.texture_path);
            view.settings.use_checkerboard = checkerboard;
        } catch (const std::exception& e) {
            session.log().warning(std::string("the session's texture: ") + e.what());
        }
    }
    scene_->update_texture();
    scene_->state_changed(session.document().area);  // the new colouring, uploaded again
}

void Viewer::start_recovery() {
    // Journals of viewers that are gone, looked for before this one's exists.
    const std::vector<OrphanJournal> orphans = find_orphan_journals();
    context_.session.start_journal(JournalOptions{});
    if (orphans.empty()) {
        if (options_.restore)
            context_.session.log().warning("--restore: no crash journal in " +
                                           default_recovery_directory());
        return;
    }
    const OrphanJournal& newest = orphans.front();
    if (options_.restore) {
        context_.session.log().info("--restore: restoring " + newest.path);
        context_.session.execute(RecoverJournal{newest.path, true});
        script_->restore_started();  // --op waits for the restore
        return;
    }
    char when[64] = "";
    const std::time_t t = std::time_t(newest.modified);
    if (std::tm tm{}; localtime_r(&t, &tm))
        std::strftime(when, sizeof(when), "%Y-%m-%d %H:%M", &tm);
    char description[512];
    std::snprintf(description, sizeof(description), "%s (%.1f kB, written %s, process %u)",
                  newest.path.c_str(), double(newest.bytes) / 1024.0, when, newest.pid);
    if (options_.frames > 0) {  // scripted runs never ask
        const std::string found = newest.ended.empty()
                                      ? "a crash journal was found: "
                                      : "unsaved work was found (its viewer was ended by " +
                                            newest.ended + " before saving): ";
        context_.session.log().info(found + description + "; trilab --restore restores it");
        return;
    }
    RecoveryPrompt& prompt = context_.panels.recovery;
    prompt.open_requested = true;
    prompt.path = newest.path;
    prompt.description = description;
    prompt.ended = newest.ended;
}

void Viewer::journal_settings() {
    if (!context_.session.files().journal()) return;
    const double now = context_.session.now();
    if (settings_journaled_at_ >= 0 && now - settings_journaled_at_ < 1.0) return;
    settings_journaled_at_ = now;
    std::string text = session_extras().viewer_settings;
    if (text == journaled_settings_) return;
    journaled_settings_ = text;
    context_.session.execute(JournalSettings{std::move(text)});
}

std::string Viewer::save_session_now() {
    try {
        SessionExtras extras = session_extras();
        if (!extras.texture_path.empty())
            extras.texture_bytes = read_file_bytes(scene_->texture_path());
        const SessionWriteReport report =
            write_session(options_.save_session, context_.session.history().snapshot(), extras);
        char buf[160];
        std::snprintf(buf, sizeof(buf), " (%zu entries, %zu states, %zu bytes)", report.entries,
                      report.states, report.bytes);
        context_.session.log().info("saved session " + options_.save_session + buf);
        return "";
    } catch (const std::exception& e) {
        return e.what();
    }
}

}  // namespace trilab::viewer
