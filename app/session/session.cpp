// The session's documents, commands, jobs and morph; see session.h. Previews and the level of
// detail are in session_preview.cpp, the frequency band in session_frequency.cpp.
#include "app/session/session.h"

#include "core/algorithms/selection.h"

#include "app/ops/operation_entries.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <thread>
#include <utility>

#include "core/algorithms/coincident.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_stats.h"
#include "core/algorithms/orientation.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"

namespace trilab::viewer {
namespace {

/// Whether every step of `result` is `mesh` itself: the same connectivity and positions, bit
/// for bit (what the history would store and the morph would show).
bool leaves_unchanged(const HalfedgeMesh& mesh, const OperationResult& result) {
    for (const OperationStep& step : result.steps) {
        const HalfedgeMesh& m = step.mesh;
        if (m.revision() == mesh.revision()) continue;
        if (m.topology_revision() != mesh.topology_revision() ||
            m.vertices_size() != mesh.vertices_size())
            return false;
        if (m.positions() != mesh.positions()) return false;
    }
    return true;
}

using Clock = std::chrono::steady_clock;
const Clock::time_point kEpoch = Clock::now();

}  // namespace

Session::Session() {
    push_loaded(make_default_model(), "Default model", "default model", "", LoadReport{});
    document_.unsaved = false;
    events_ = SessionEvents{};
    events_.state_changed = events_.fit = true;
}

Session::~Session() = default;

double Session::now() const {
    return std::chrono::duration<double>(Clock::now() - kEpoch).count();
}

SessionEvents Session::take_events() {
    SessionEvents e = std::move(events_);
    events_ = SessionEvents{};
    return e;
}

void Session::notify_error(const std::string& text) {
    log_.error(text);
    notice_ = Notice{Notice::Level::Error, text, {}, true};
}

void Session::notify(Notice notice) {
    notice_ = std::move(notice);
}

void Session::busy_error() {
    notify_error("busy: wait for \"" + jobs_.name() + "\" or cancel it");
}

void Session::log_history_messages(const std::vector<std::string>& messages) {
    for (const std::string& m : messages) log_.warning(m);
}

void Session::push_loaded(HalfedgeMesh mesh, std::string label, std::string name, std::string path,
                          LoadReport report) {
    // A load shows no motion: every vertex "starts" where it is.
    MorphCorrespondence none{MorphCorrespondence::Kind::FromEarlier, mesh.positions()};
    // "Load bunny.obj ../meshes/bunny.obj"; the path alone where it is the name.
    const std::string parameters = path == name ? "" : path;
    // The first file replaces the built-in model while nothing was done to it.
    const bool untouched_default =
        document_.history.size() == 1 && document_.path.empty() && !document_.unsaved;
    if (document_.history.size() == 0 || untouched_default)
        document_.history.reset(std::move(mesh), std::move(label), parameters);
    else
        log_history_messages(document_.history.push(std::move(label), parameters, 0.0,
                                                    {std::move(mesh)}, {std::move(none)}));
    document_.name = std::move(name);
    document_.path = std::move(path);
    document_.report = std::move(report);
    on_state_changed(true);
    document_.unsaved = false;
}

void Session::on_state_changed(bool fit) {
    clear_level_of_detail(true);  // a level of detail belongs to the state it was built on
    document_.unsaved = true;
    const HalfedgeMesh& mesh = document_.mesh();
    document_.texcoords_projected =
        mesh.has_vertex_property("v:texcoord") && document_.texcoords_projected;
    auto components = std::make_shared<std::vector<Index>>();
    const MeshStats s = compute_stats(mesh, components.get());
    document_.components = std::move(components);
    document_.components_topology = mesh.topology_revision();
    document_.closed = s.volume.has_value();
    document_.open_seams = s.boundary_loops > 0 && pair_boundary_edges(mesh).paired_edges > 0;
    document_.area = s.area;
    char buf[256];
    std::vector<std::string>& info = document_.info;
    info.clear();
    info.push_back("model: " + document_.name +
                   (document_.path.empty() ? "" : " (" + document_.path + ")"));
    const History::EntryInfo entry = document_.history.info(document_.history.current());
    const std::string state = "state " + std::to_string(document_.history.current()) + " of " +
                              std::to_string(document_.history.size()) + ": " + entry.label +
                              (entry.parameters.empty() ? "" : " " + entry.parameters);
    info.push_back(state);
    std::snprintf(buf, sizeof(buf), "vertices %zu (%zu isolated), edges %zu, faces %zu", s.vertices,
                  s.isolated_vertices, s.edges, s.faces);
    info.push_back(buf);
    std::snprintf(buf, sizeof(buf), "components %zu, boundary loops %zu, Euler %lld, genus %lld",
                  s.components, s.boundary_loops, s.euler, s.genus);
    info.push_back(buf);
    std::snprintf(buf, sizeof(buf), "bounding box [%g %g %g] - [%g %g %g]", s.bbox.min.x(),
                  s.bbox.min.y(), s.bbox.min.z(), s.bbox.max.x(), s.bbox.max.y(), s.bbox.max.z());
    info.push_back(buf);
    if (s.volume)
        std::snprintf(buf, sizeof(buf), "area %.6g, volume %.6g", s.area, *s.volume);
    else
        std::snprintf(buf, sizeof(buf), "area %.6g, volume undefined (open mesh)", s.area);
    info.push_back(buf);
    for (const std::string& line : document_.report.lines()) info.push_back("load: " + line);

    morph_ = MorphState{1.0, false, morph_.duration, morph_.easing, morph_.playback, 0.0};
    morph_.moves = entry_moves();
    // The status bar tells where the document is now (a load says more afterwards).
    notice_ = Notice{Notice::Level::Info,
                     "state " + std::to_string(document_.history.current()) + ": " + entry.label +
                         (entry.parameters.empty() ? "" : " " + entry.parameters),
                     {},
                     false};
    update_frequency_document();
    show_document();
    if (journal_) journal_->record(document_.history.snapshot());  // queues only
    events_.state_changed = true;
    events_.fit = events_.fit || fit;
}

void Session::show_document() {
    shown_.kind = Shown::Kind::Document;
    shown_.mesh = &document_.mesh();
    shown_.positions.clear();
    shown_.level = nullptr;
    bump();
    follow_picks();
}

void Session::execute(const Command& command) {
    if (execute_selection(command)) return;
    if (execute_morph(command)) return;
    if (auto* c = std::get_if<LoadFile>(&command)) {
        clear_preview();
        if (is_session_path(c->path))
            open_session(c->path);
        else
            load(c->path);
    } else if (auto* save_file = std::get_if<SaveFile>(&command)) {
        if (is_session_path(save_file->path))
            save_session(save_file->path, {});
        else
            save(save_file->path);
    } else if (auto* save_session_command = std::get_if<SaveSession>(&command)) {
        save_session(save_session_command->path, {});
    } else if (auto* open = std::get_if<OpenSession>(&command)) {
        clear_preview();
        open_session(open->path);
    } else if (std::holds_alternative<RevertFile>(command)) {
        if (is_session_path(document_.path))
            open_session(document_.path);
        else if (!document_.path.empty())
            load(document_.path);
    } else if (auto* texture = std::get_if<LoadTexture>(&command)) {
        load_texture(texture->path);
    } else if (std::holds_alternative<Undo>(command) || std::holds_alternative<Redo>(command) ||
               std::holds_alternative<JumpTo>(command)) {
        History& h = document_.history;
        clear_preview();  // a preview belongs to the state it was computed on
        clear_level_of_detail(true);
        if (jobs_.busy()) return busy_error();
        if (std::holds_alternative<Undo>(command) && h.can_undo())
            h.undo();
        else if (std::holds_alternative<Redo>(command) && h.can_redo())
            h.redo();
        else if (auto* jump = std::get_if<JumpTo>(&command); jump && jump->entry < h.size())
            h.jump(jump->entry);
        else
            return;
        log_.info("now at state " + std::to_string(h.current()) + ": " + h.info(h.current()).label);
        on_state_changed(false);
    } else if (auto* op = std::get_if<RunOperation>(&command)) {
        clear_preview();
        run_operation_job(op->op);
    } else if (auto* preview = std::get_if<PreviewOperation>(&command)) {
        request_preview(preview->op);
    } else if (auto* apply = std::get_if<ApplyOperation>(&command)) {
        apply_operation(apply->op);
    } else if (std::holds_alternative<CancelPreview>(command)) {
        clear_preview();
        clear_level_of_detail(false);
    } else if (auto* build = std::get_if<BuildLevelOfDetail>(&command)) {
        build_level_of_detail(build->op);
    } else if (auto* show = std::get_if<ShowLevelOfDetail>(&command)) {
        show_level_of_detail(show->percent);
    } else if (std::holds_alternative<ApplyLevelOfDetail>(command)) {
        apply_level_of_detail();
    } else if (auto* d = std::get_if<Decompose>(&command)) {
        decompose(spectral_options(d->op));
    } else if (auto* band = std::get_if<PreviewBand>(&command)) {
        preview_band(band->lo, band->hi);
    } else if (auto* commit = std::get_if<CommitBand>(&command)) {
        push_band(commit->lo, commit->hi, false);
    } else if (std::holds_alternative<RestoreDecomposed>(command)) {
        push_band(0, 0, true);
    } else if (std::holds_alternative<CancelJob>(command)) {
        jobs_.cancel();
    } else if (auto* figure = std::get_if<LoadFigure>(&command)) {
        load_figure(figure->name);
    }
}

std::shared_ptr<const LoadingPicture> Session::loading_picture() const {
    const std::lock_guard<std::mutex> lock(picture_slot_->mutex);
    return picture_slot_->picture;
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

void Session::load(const std::string& path) {
    const std::string name = std::filesystem::path(path).filename().string();
    const bool started =
        jobs_.start("Loading " + name, [this, path, name, slot = picture_slot_,
                                        maker = loading_picture_maker_](Progress& progress) {
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
                log_.info("loaded " + path);
                for (const std::string& line : loaded->report.lines()) {
                    if (line == *inward)
                        log_.warning("  " + line);
                    else
                        log_.info("  " + line);
                }
                if (!loaded->texture_path.empty()) log_.info("  texture: " + loaded->texture_path);
                const bool revert = path == document_.path;
                std::vector<std::string> report_lines = loaded->report.lines();
                push_loaded(std::move(loaded->mesh), revert ? "Revert" : "Load " + name, name, path,
                            std::move(loaded->report));
                notice_ = Notice{Notice::Level::Info, (revert ? "Reverted to " : "Loaded ") + name,
                                 std::move(report_lines), false};
                if (!inward->empty())
                    notice_.text +=
                        ": its faces point inwards (negative volume); Tools > Flip "
                        "orientation turns them outwards";
                events_.recent.push_back(path);
                events_.loaded_proxy = picture_proxy;
            });
        });
    if (!started) busy_error();
}

void Session::save(const std::string& path) {
    const HalfedgeMesh snapshot = document_.mesh();  // copy-on-write: the job's own
    const std::string name = std::filesystem::path(path).filename().string();
    const bool started =
        jobs_.start("Saving " + name, [this, snapshot, path, name](Progress& progress) {
            progress.report(-1.0, "writing");
            write_mesh(snapshot, path);
            return JobRunner::Finish([this, path, name] {
                notice_ = Notice{Notice::Level::Info, "Saved " + name, {}, false};
                log_.info("saved " + path);
                events_.recent.push_back(path);
                events_.saved = true;
                document_.unsaved = false;
            });
        });
    if (!started) busy_error();
}

void Session::load_texture(const std::string& path) {
    const std::string name = std::filesystem::path(path).filename().string();
    const bool started = jobs_.start("Loading texture " + name, [this, path, name](Progress&) {
        auto image = std::make_shared<Image>(read_image(path));
        return JobRunner::Finish([this, image, path, name] {
            log_.info("texture " + path + ": " + std::to_string(image->width) + " x " +
                      std::to_string(image->height));
            notice_ = Notice{Notice::Level::Info, "Texture " + name, {}, false};
            events_.texture = image;
            events_.texture_path = path;
        });
    });
    if (!started) busy_error();
}

std::shared_ptr<const std::vector<float>> Session::region_for(const Operation& op,
                                                              const HalfedgeMesh& mesh) const {
    if (!op.def || !op.def->takes_region) return nullptr;
    std::optional<Selection> selection = stored_selection(mesh);
    if (!selection || selects_everything(mesh, *selection)) return nullptr;
    return std::make_shared<const std::vector<float>>(std::move(*selection));
}

bool Session::poll() {
    start_pick_job();
    take_inspection();
    const JobRunner::Outcome outcome = jobs_.poll();
    using Kind = JobRunner::Outcome::Kind;
    if (outcome.kind == Kind::None) return false;
    {
        // The job ended (loaded, failed or cancelled): its loading picture goes.
        const std::lock_guard<std::mutex> lock(picture_slot_->mutex);
        picture_slot_->picture.reset();
    }
    const bool preview = outcome.name.rfind("Preview: ", 0) == 0;
    if (preview && outcome.kind == Kind::Failed) preview_.failure = outcome.message;
    if (preview && outcome.kind != Kind::Failed) {
        if (outcome.kind == Kind::Succeeded && preview_.requested &&
            preview_.computed_op == *preview_.requested)
            preview_.latency_ms = 1000.0 * (now() - preview_.requested_at);
        return true;
    }
    if (outcome.kind == Kind::Failed) {
        notify_error(outcome.message);
    } else if (outcome.kind == Kind::Cancelled) {
        log_.warning(outcome.name + ": cancelled, nothing changed");
        notice_ = Notice{Notice::Level::Info, outcome.name + ": cancelled", {}, false};
    } else {
        char buf[64];
        std::snprintf(buf, sizeof(buf), " (%.0f ms)", outcome.seconds * 1000.0);
        log_.info(outcome.name + " done" + buf);
    }
    return true;
}

void Session::finish_jobs() {
    while (jobs_.busy() || preview_.pending || preview_.prediction_job.valid()) {
        collect_prediction_job();
        start_pending_preview();
        poll();
        if (jobs_.busy() || preview_.prediction_job.valid())
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    poll();
}

void Session::run_operation_job(const Operation& op) {
    try {
        check_operation(op);
    } catch (const std::exception& e) {
        notify_error(e.what());
        return;
    }
    const HalfedgeMesh snapshot = document_.mesh();  // copy-on-write: the job's own
    const HalfedgeMesh::Revision base = snapshot.revision();
    const auto region = region_for(op, snapshot);
    // The state's components, when the run has a region (a flip then need not find them).
    const std::shared_ptr<const std::vector<Index>> components =
        region && document_.components_topology == snapshot.topology_revision()
            ? document_.components
            : nullptr;
    const bool started =
        jobs_.start(op.text(), [this, op, snapshot, base, region, components](Progress& progress) {
            RunSettings settings;
            settings.region = region.get();
            settings.components = components.get();
            auto result =
                std::make_shared<OperationResult>(run_operation(op, snapshot, progress, settings));
            return JobRunner::Finish([this, result, op, base] {
                // The result belongs to the state it was computed on: never stacked on another.
                if (document_.mesh().revision() != base) {
                    notify_error(result->label +
                                 ": the document changed while it ran; its result is not applied");
                    return;
                }
                commit_result(op, std::move(*result));
            });
        });
    if (!started) busy_error();
}

void Session::commit_result(const Operation& op, OperationResult result_value) {
    OperationResult* result = &result_value;
    if (!result->changed) {  // stopped before its first good iteration: nothing to keep
        for (const std::string& line : result->report) log_.info("  " + line);
        notify_error(result->label + " stopped early, nothing changed: " + result->stop_reason);
        return;
    }
    // A run that changed nothing (a step of 0, no edge to weld) adds no entry, and says so.
    if (leaves_unchanged(document_.mesh(), *result)) {
        for (const std::string& line : result->report) log_.info("  " + line);
        const std::string text =
            result->label + " " + result->parameters + " changed nothing: no history entry";
        log_.info(text);
        notice_ = Notice{Notice::Level::Info, text, {}, false};
        return;
    }
    std::vector<HalfedgeMesh> meshes;
    std::vector<MorphCorrespondence> correspondences;
    for (OperationStep& step : result->steps) {
        meshes.push_back(std::move(step.mesh));
        correspondences.push_back(std::move(step.correspondence));
    }
    log_history_messages(document_.history.push(result->label, result->parameters, result->ms,
                                                std::move(meshes), std::move(correspondences), op));
    log_.info(result->label + " " + result->parameters);
    for (const std::string& line : result->report) log_.info("  " + line);
    on_state_changed(false);
    if (is_operation<FlipOptions>(op)) {  // replaces a load's "its faces point inwards"
        std::string text = result->label;
        for (std::size_t i = 0; i < result->report.size(); ++i)
            text += (i ? "; " : ": ") + result->report[i];
        notice_ = Notice{Notice::Level::Info, text, {}, false};
    }
    // A run that stopped early keeps its good steps and says why, never silently.
    if (result->stopped_early)
        notify_error(result->label + " stopped early: " + result->stop_reason);
    // Show the change: play the morph once from before to after.
    morph_.t = 0.0;
    morph_.playing = true;
    morph_.playback = Playback::Once;
    morph_.play_start = now();
}

void Session::project_texcoords(TexCoordProjection projection, UpAxis up) {
    if (jobs_.busy()) return busy_error();
    HalfedgeMesh textured = document_.mesh();
    trilab::project_texcoords(textured, projection, up);
    const bool planar = projection == TexCoordProjection::Planar;
    const std::string kind =
        planar ? "planar" : std::string("spherical, +") + up_axis_name(up) + " up";
    // An entry of its own, so it can be undone; the shape does not move.
    log_history_messages(document_.history.push("Texture coordinates", kind, 0.0,
                                                {std::move(textured)}, {MorphCorrespondence{}}));
    document_.texcoords_projected = true;
    on_state_changed(false);
    log_.info(kind + " texture coordinates computed on the current shape");
}

std::vector<Point> Session::reference_positions() const {
    // The state before the current entry, on the current connectivity: the morph's start.
    const History& history = document_.history;
    if (history.size() == 0 || history.current() == 0) return {};
    try {
        MorphFrame start = history.morph(history.current(), 0.0);
        if (start.topology && start.positions.size() == document_.mesh().vertices_size())
            return std::move(start.positions);
    } catch (const std::exception&) {
        // No usable earlier state: the colouring says so.
    }
    return {};
}

bool Session::entry_moves() const {
    const History& h = document_.history;
    const std::size_t entry = h.current();
    if (h.size() == 0 || entry == 0) return false;
    const History::EntryInfo info = h.info(entry);
    // Operations move vertices; a state the session made itself (a load, a revert, texture
    // coordinates) may not: compare its start with its end.
    if (info.operation.def || info.steps.size() != 1) return true;
    try {
        const MorphFrame start = h.morph(entry, 0.0);
        const HalfedgeMesh& mesh = document_.mesh();
        if (!start.topology || start.positions.size() != mesh.vertices_size()) return true;
        for (Vertex v : mesh.vertices())
            if (start.positions[v.idx()] != mesh.position(v)) return true;
    } catch (const std::exception&) {
        return true;
    }
    return false;
}

void Session::update() {
    collect_prediction_job();
    start_pending_preview();
    if (shown_.kind == Shown::Kind::Level || shown_.kind == Shown::Kind::Band) return;
    if (prediction_shown()) return;  // the newest request's prediction, until its exact result
    if (preview_.result) {
        show_preview();
        return;
    }
    update_morph();
}

bool Session::execute_morph(const Command& command) {
    if (auto* play = std::get_if<PlayMorph>(&command)) {
        if (play->play && !morph_.playing) {
            // A pass from the start, on the session's clock.
            morph_.playing = true;
            morph_.play_start = now();
        } else if (!play->play) {
            morph_.playing = false;
        }
    } else if (auto* at = std::get_if<ShowMorphAt>(&command)) {
        morph_.t = std::isfinite(at->t) ? std::clamp(at->t, 0.0, 1.0) : 1.0;
        morph_.playing = false;
    } else if (auto* a = std::get_if<SetMorphAnimation>(&command)) {
        if (std::isfinite(a->duration) && a->duration > 0) morph_.duration = a->duration;
        morph_.easing = a->easing;
        morph_.playback = a->playback;
    } else if (auto* diverging = std::get_if<ShowDivergingRun>(&command)) {
        if (!busy()) show_diverging_run(diverging->op);
    } else if (std::holds_alternative<NoticeShown>(command)) {
        notice_.popup_pending = false;
    } else if (auto* c = std::get_if<ComputeColoring>(&command)) {
        if (jobs_.busy()) {
            busy_error();
            return true;
        }
        const HalfedgeMesh snapshot = mesh();  // copy-on-write: the job's own
        jobs_.start(std::string("Colouring by ") + coloring_name(c->coloring),
                    [this, c = *c, snapshot](Progress&) {
                        auto result = std::make_shared<ColoringResult>();
                        result->coloring = c.coloring;
                        result->state = snapshot.revision();
                        result->colors =
                            color_vertices(snapshot, c.coloring, c.options, c.reference.get());
                        return JobRunner::Finish([this, result] {
                            result->id = (coloring_result_ ? coloring_result_->id : 0) + 1;
                            coloring_result_ = result;
                        });
                    });
    } else {
        return false;
    }
    return true;
}

void Session::update_morph() {
    const std::size_t entry = document_.history.current();
    if (morph_.playing) {
        morph_.t = playback_time(morph_.playback, now() - morph_.play_start, morph_.duration);
        if (morph_.playback == Playback::Once && morph_.t >= 1.0) morph_.playing = false;
    }
    const bool morphing = entry > 0 && (morph_.playing || morph_.t < 1.0);
    if (!morphing) {
        if (shown_.kind != Shown::Kind::Document) show_document();
        return;
    }
    try {
        MorphFrame frame = document_.history.morph(entry, ease(morph_.easing, morph_.t));
        shown_.kind = Shown::Kind::Morph;
        shown_.mesh = frame.topology;
        shown_.positions = std::move(frame.positions);
        shown_.level = nullptr;
        bump();
    } catch (const std::exception& e) {
        morph_ = MorphState{1.0, false,       morph_.duration, morph_.easing, morph_.playback,
                            0.0, morph_.moves};
        notify_error(std::string("morph: ") + e.what());
        show_document();
    }
}

}  // namespace trilab::viewer
