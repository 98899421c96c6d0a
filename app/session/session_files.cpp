// Session files and the crash journal of a Session (see session.h): saving and opening the
// whole history as a job, restoring it, and journaling every history change.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <utility>

#include "app/session/session.h"
#include "core/io/file_util.h"

namespace trilab::viewer {

bool is_session_path(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".trilab" || ext == ".journal";
}

void Session::save_session(const std::string& path, SessionExtras extras) {
    if (document_.history.size() == 0) return notify_error("save session: there is no history");
    History::Snapshot snapshot = document_.history.snapshot();  // a pointer per entry
    const std::string name = std::filesystem::path(path).filename().string();
    auto shared_extras = std::make_shared<SessionExtras>(std::move(extras));
    const bool started = jobs_.start(
        "Saving session " + name, [this, snapshot, shared_extras, path, name](Progress& progress) {
            progress.report(-1.0, "writing every state");
            auto note = std::make_shared<std::string>();
            SessionExtras& e = *shared_extras;
            if (!e.texture_path.empty() && e.texture_bytes.empty()) {
                try {
                    e.texture_bytes = read_file_bytes(e.texture_path);
                } catch (const std::exception& error) {
                    *note = std::string("the texture is stored by its path only: ") + error.what();
                }
            }
            auto report = std::make_shared<SessionWriteReport>(write_session(path, snapshot, e));
            return JobRunner::Finish([this, report, note, path, name] {
                char buf[160];
                std::snprintf(buf, sizeof(buf), " (%zu entries, %zu states, %zu bytes)",
                              report->entries, report->states, report->bytes);
                log_.info("saved session " + path + buf);
                if (!note->empty()) log_.warning("  " + *note);
                for (const std::string& s : report->skipped) log_.warning("  not stored: " + s);
                notice_ = Notice{Notice::Level::Info, "Saved session " + name, {}, false};
                events_.recent.push_back(path);
                events_.saved = true;
                events_.continue_after_save = continue_after_save_;
                continue_after_save_ = false;
                document_.unsaved = false;
            });
        });
    if (!started) busy_error();
}

void Session::open_session(const std::string& path, bool remove_after) {
    const std::string name = std::filesystem::path(path).filename().string();
    const std::size_t budget = document_.history.budget();
    const bool started = jobs_.start("Opening session " + name, [this, path, budget,
                                                                 remove_after](Progress& progress) {
        progress.report(-1.0, "reading every state");
        auto contents = std::make_shared<SessionContents>(read_session_or_journal(path, budget));
        return JobRunner::Finish([this, contents, path, remove_after] {
            restore_session(std::move(*contents), path);
            if (remove_after) {
                std::error_code ec;
                std::filesystem::remove(path, ec);
            }
        });
    });
    if (!started) busy_error();
}

void Session::restore_session(SessionContents contents, const std::string& path) {
    clear_preview();
    clear_level_of_detail(true);
    const std::size_t budget = document_.history.budget();
    document_.history = std::move(contents.history);
    document_.history.set_budget(budget);
    log_history_messages(contents.messages);
    log_history_messages(document_.history.trim_to_budget());
    const std::string name = std::filesystem::path(path).filename().string();
    document_.name = name;
    // A journal is no document of its own: Save asks for a file name.
    document_.path = contents.journal ? std::string() : path;
    document_.report = LoadReport{};
    document_.texcoords_projected = false;
    document_.frequency = FrequencyDocument{};
    on_state_changed(true);
    document_.unsaved = contents.journal;
    const std::size_t n = document_.history.size();
    std::string text = (contents.journal ? "Recovered " : "Opened session ") + name + ": " +
                       std::to_string(n) + " entries, state " +
                       std::to_string(document_.history.current());
    log_.info((contents.journal ? "recovered " : "opened session ") + path + ": " +
              std::to_string(n) + " entries");
    if (contents.journal && !contents.complete) {
        const std::string lost =
            "the journal ends in an incomplete record: " + std::to_string(contents.records) +
            " changes recovered, " + std::to_string(contents.bytes_discarded) +
            " bytes discarded (" + contents.stop_reason + ")";
        log_.warning("  " + lost);
        text += "; " + lost;
    }
    notice_ = Notice{Notice::Level::Info, text, {}, false};
    events_.recent.push_back(path);
    events_.session_extras = std::make_shared<SessionExtras>(std::move(contents.extras));
}

void Session::start_journal(JournalOptions options) {
    journal_ = std::make_unique<Journal>(std::move(options));
    if (document_.history.size() > 0) journal_->record(document_.history.snapshot());
}

void Session::close_journal() {
    if (!journal_) return;
    try {
        journal_->close();
    } catch (const std::exception& e) {
        log_.warning(std::string("crash journal: ") + e.what());
    }
    journal_.reset();
}

}  // namespace trilab::viewer
