// Files, session files and the crash journal; see session_files.h.
#include "app/session/session_files.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <thread>
#include <utility>

#include "core/algorithms/orientation.h"
#include "core/io/file_util.h"
#include "core/io/mesh_io.h"

namespace trilab::viewer {

namespace {

/// "bunny.obj (recovered)": the model the newest load at or before the current entry read,
/// or the first entry's title.
std::string recovered_name(const History& history) {
    std::string name;
    for (std::size_t i = 0; i < history.size() && i <= history.current(); ++i) {
        const std::string label = history.info(i).label;
        if (label.rfind("Load ", 0) == 0 && label.size() > 5)
            name = label.substr(5);
        else if (name.empty())
            name = label;
    }
    return (name.empty() ? std::string("work") : name) + " (recovered)";
}

}  // namespace

bool SessionFiles::asks_before_discarding(bool discard_changes, const std::string& path) {
    if (discard_changes || !ask_before_discarding_ || !core_.document.unsaved) return false;
    core_.log.info("unsaved changes: asking before opening " + path);
    core_.events.confirm_discard = path;
    return true;
}

bool SessionFiles::execute(const Command& command) {
    const Document& document = core_.document;
    if (auto* c = std::get_if<LoadFile>(&command)) {
        if (asks_before_discarding(c->discard_changes, c->path)) return true;
        previews_.clear();
        if (is_session_path(c->path))
            open_session(c->path);
        else
            load(c->path);
    } else if (auto* save_file = std::get_if<SaveFile>(&command)) {
        continue_after_save_ = save_file->then_continue;
        if (is_session_path(save_file->path))  // a session's own file: the whole session
            save_session(save_file->path);
        else
            save(save_file->path);
    } else if (auto* save_session_command = std::get_if<SaveSession>(&command)) {
        continue_after_save_ = false;
        save_session(save_session_command->path);
    } else if (auto* open = std::get_if<OpenSession>(&command)) {
        if (asks_before_discarding(open->discard_changes, open->path)) return true;
        previews_.clear();
        open_session(open->path);
    } else if (auto* recover = std::get_if<RecoverJournal>(&command)) {
        if (!recover->restore) {
            remove_journal(recover->path);
            core_.log.info("discarded the crash journal " + recover->path);
        } else if (asks_before_discarding(recover->discard_changes, recover->path)) {
            core_.events.confirm_recovery = true;
        } else {
            previews_.clear();
            open_session(recover->path, true);
        }
    } else if (std::holds_alternative<RevertFile>(command)) {
        if (is_session_path(document.path))
            open_session(document.path);
        else if (!document.path.empty())
            load(document.path);
    } else if (auto* texture = std::get_if<LoadTexture>(&command)) {
        load_texture(texture->path);
    } else if (auto* settings = std::get_if<JournalSettings>(&command)) {
        if (journal_) journal_->record_viewer_settings(settings->text);  // queues only
    } else {
        return false;
    }
    return true;
}

std::shared_ptr<const LoadingPicture> SessionFiles::loading_picture() const {
    const std::lock_guard<std::mutex> lock(picture_slot_->mutex);
    return picture_slot_->picture;
}

void SessionFiles::job_ended() {
    const std::lock_guard<std::mutex> lock(picture_slot_->mutex);
    picture_slot_->picture.reset();
}

void SessionFiles::saved(const std::string& path) {
    core_.events.recent.push_back(path);
    core_.events.saved = true;
    core_.events.continue_after_save = continue_after_save_;
    continue_after_save_ = false;
    core_.document.unsaved = false;
}

namespace {

/// The picture of `soup` (null when `maker` makes none), its bounds and fit sphere as the
/// window's fit_view computes them for the mesh.
std::shared_ptr<const LoadingPicture> make_loading_picture(const LoadingPictureMaker& maker,
                                                           const PolygonSoup& soup,
                                                           const std::string& path) {
    std::shared_ptr<const ProxyMesh> proxy = maker(soup);
    if (!proxy) return nullptr;
    auto picture = std::make_shared<LoadingPicture>();
    picture->path = path;
    picture->proxy = std::move(proxy);
    picture->faces = soup.n_faces();
    for (const Point& p : soup.positions) picture->bounds.extend(p);
    picture->center = picture->bounds.empty ? Point::Zero() : picture->bounds.center();
    double radius2 = 0;
    for (const Point& p : soup.positions)
        radius2 = std::max(radius2, (p - picture->center).squaredNorm());
    picture->radius = std::sqrt(radius2);
    return picture;
}

/// Tests only: milliseconds the load job waits once its picture is shown (so that a
/// scripted run sees the picture before the exact surface, whatever the machine's speed).
int loading_picture_hold_ms() {
    const char* env = std::getenv("TRILAB_LOADING_PICTURE_HOLD_MS");
    return env && *env ? std::max(0, std::atoi(env)) : 0;
}

}  // namespace

void SessionFiles::load(const std::string& path) {
    const std::string name = std::filesystem::path(path).filename().string();
    const bool started = core_.jobs.start(
        "Loading " + name,
        [this, path, name, slot = picture_slot_, maker = picture_maker_](Progress& progress) {
            progress.report(-1.0, "reading and building the half-edge mesh");
            // The picture is handed over through the slot (never the document), once the whole
            // file is read and checked; a failed picture only means none.
            std::shared_ptr<const ProxyMesh> picture_proxy;
            auto on_soup = [&](const PolygonSoup& soup) {
                if (!maker) return;
                std::shared_ptr<const LoadingPicture> picture;
                try {
                    picture = make_loading_picture(maker, soup, path);
                } catch (const std::exception&) {
                    return;
                }
                if (!picture) return;
                picture_proxy = picture->proxy;
                {
                    const std::lock_guard<std::mutex> lock(slot->mutex);
                    slot->picture = std::move(picture);
                }
                if (const int hold = loading_picture_hold_ms())
                    std::this_thread::sleep_for(std::chrono::milliseconds(hold));
                progress.report(-1.0, "building the half-edge mesh (a simplified picture shows)");
                progress.check_cancelled();  // a cancelled load stops before the build
            };
            auto loaded = std::make_shared<LoadedMesh>(read_mesh(path, on_soup));
            const LoadReport& r = loaded->report;
            if (r.polygons_triangulated || r.degenerate_faces_dropped || r.detached_faces ||
                r.vertex_copies_added)
                picture_proxy.reset();  // not the mesh's own proxy
            // A closed mesh turned inside out (read_mesh notes it): said where it shows.
            auto inward = std::make_shared<std::string>(inward_orientation_note(loaded->mesh));
            // Runs on this thread when the job succeeded and was not cancelled.
            return JobRunner::Finish([this, loaded, path, name, inward, picture_proxy] {
                core_.log.info("loaded " + path);
                for (const std::string& line : loaded->report.lines()) {
                    if (line == *inward)
                        core_.log.warning("  " + line);
                    else
                        core_.log.info("  " + line);
                }
                if (!loaded->texture_path.empty())
                    core_.log.info("  texture: " + loaded->texture_path);
                const bool revert = path == core_.document.path;
                std::vector<std::string> report_lines = loaded->report.lines();
                document_.push_loaded(std::move(loaded->mesh), revert ? "Revert" : "Load " + name,
                                      name, path, std::move(loaded->report));
                core_.notice =
                    Notice{Notice::Level::Info, (revert ? "Reverted to " : "Loaded ") + name,
                           std::move(report_lines), false};
                if (!inward->empty())
                    core_.notice.text +=
                        ": its faces point inwards (negative volume); Tools > Flip "
                        "orientation turns them outwards";
                core_.events.recent.push_back(path);
                core_.events.loaded_proxy = picture_proxy;
            });
        });
    if (!started) core_.busy_error();
}

void SessionFiles::save(const std::string& path) {
    const HalfedgeMesh snapshot = core_.mesh();  // copy-on-write: the job's own
    const std::string name = std::filesystem::path(path).filename().string();
    const bool started =
        core_.jobs.start("Saving " + name, [this, snapshot, path, name](Progress& progress) {
            progress.report(-1.0, "writing");
            write_mesh(snapshot, path);
            return JobRunner::Finish([this, path, name] {
                core_.inform("Saved " + name);
                core_.log.info("saved " + path);
                saved(path);
            });
        });
    if (!started) core_.busy_error();
}

void SessionFiles::load_texture(const std::string& path) {
    const std::string name = std::filesystem::path(path).filename().string();
    const bool started = core_.jobs.start("Loading texture " + name, [this, path, name](Progress&) {
        auto image = std::make_shared<Image>(read_image(path));
        return JobRunner::Finish([this, image, path, name] {
            core_.log.info("texture " + path + ": " + std::to_string(image->width) + " x " +
                           std::to_string(image->height));
            core_.inform("Texture " + name);
            core_.events.texture = image;
            core_.events.texture_path = path;
        });
    });
    if (!started) core_.busy_error();
}

void SessionFiles::save_session(const std::string& path) {
    SessionExtras extras = extras_provider_ ? extras_provider_() : SessionExtras{};
    if (core_.document.history.size() == 0)
        return core_.notify_error("save session: there is no history");
    History::Snapshot snapshot = core_.document.history.snapshot();  // a pointer per entry
    const std::string name = std::filesystem::path(path).filename().string();
    auto shared_extras = std::make_shared<SessionExtras>(std::move(extras));
    const bool started = core_.jobs.start(
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
                core_.log.info("saved session " + path + buf);
                if (!note->empty()) core_.log.warning("  " + *note);
                for (const std::string& s : report->skipped)
                    core_.log.warning("  not stored: " + s);
                core_.inform("Saved session " + name);
                saved(path);
            });
        });
    if (!started) core_.busy_error();
}

void SessionFiles::open_session(const std::string& path, bool remove_after) {
    const std::string name = std::filesystem::path(path).filename().string();
    const std::size_t budget = core_.document.history.budget();
    const bool started = core_.jobs.start(
        "Opening session " + name, [this, path, budget, remove_after](Progress& progress) {
            progress.report(-1.0, "reading every state");
            auto contents =
                std::make_shared<SessionContents>(read_session_or_journal(path, budget));
            return JobRunner::Finish([this, contents, path, remove_after] {
                restore_session(std::move(*contents), path);
                if (remove_after) remove_journal(path);
            });
        });
    if (!started) core_.busy_error();
}

void SessionFiles::restore_session(SessionContents contents, const std::string& path) {
    previews_.clear();
    Document& document = core_.document;
    const std::size_t budget = core_.document.history.budget();
    core_.document.history = std::move(contents.history);
    core_.document.history.set_budget(budget);
    core_.log_history_messages(contents.messages);
    core_.log_history_messages(core_.document.history.trim_to_budget());
    const std::string name = std::filesystem::path(path).filename().string();
    // A journal is named after the model it holds (its file is removed once restored).
    document.name = contents.journal ? recovered_name(core_.document.history) : name;
    // A journal is no document of its own: Save asks for a file name.
    document.path = contents.journal ? std::string() : path;
    document.report = LoadReport{};
    document.texcoords_projected = false;
    document.frequency = FrequencyDocument{};
    core_.state_changed(true);
    document.unsaved = contents.journal;
    const std::size_t n = core_.document.history.size();
    std::string text = (contents.journal ? "Recovered " : "Opened session ") + name + ": " +
                       std::to_string(n) + " entries, state " +
                       std::to_string(core_.document.history.current());
    core_.log.info((contents.journal ? "recovered " : "opened session ") + path + ": " +
                   std::to_string(n) + " entries");
    if (contents.journal && !contents.complete) {
        const std::string lost =
            "the journal ends in an incomplete record: " + std::to_string(contents.records) +
            " changes recovered, " + std::to_string(contents.bytes_discarded) +
            " bytes discarded (" + contents.stop_reason + ")";
        core_.log.warning("  " + lost);
        text += "; " + lost;
    }
    core_.inform(text);
    core_.events.recent.push_back(path);
    core_.events.session_extras = std::make_shared<SessionExtras>(std::move(contents.extras));
}

void SessionFiles::start_journal(JournalOptions options) {
    journal_ = std::make_unique<Journal>(std::move(options));
    record();
}

void SessionFiles::record() {
    if (journal_ && core_.document.history.size() > 0)
        journal_->record(core_.document.history.snapshot());  // queues only
}

void SessionFiles::check_journal() {
    if (!journal_) return;
    const std::string warning = journal_->take_warning();
    if (warning.empty()) return;
    core_.log.warning("crash journal: " + warning);
    core_.notice = Notice{Notice::Level::Error, "crash journal stopped: " + warning, {}, false};
}

void SessionFiles::flush_journal() {
    if (journal_) journal_->flush();
}

void SessionFiles::end_journal_unsaved(const std::string& how) {
    if (!journal_) return;
    journal_->end_unsaved(how);
    journal_.reset();
}

void SessionFiles::close_journal() {
    if (!journal_) return;
    try {
        journal_->close();
    } catch (const std::exception& e) {
        core_.log.warning(std::string("crash journal: ") + e.what());
    }
    journal_.reset();
}

}  // namespace trilab::viewer
