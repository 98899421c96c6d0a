// The session's document and history owner; see session_document.h.
#include "app/session/session_document.h"

#include <cstdio>
#include <utility>

#include "app/ops/operation_entries.h"
#include "core/algorithms/coincident.h"
#include "core/algorithms/mesh_stats.h"
#include "core/algorithms/orientation.h"
#include "core/algorithms/selection.h"

namespace trilab::viewer {
namespace {

/// Whether every step of `result` is `mesh` itself: the same connectivity, properties and
/// positions, bit for bit (what the history would store and the morph would show).
bool leaves_unchanged(const HalfedgeMesh& mesh, const OperationResult& result) {
    for (const OperationStep& step : result.steps) {
        const HalfedgeMesh& m = step.mesh;
        if (m.revision() == mesh.revision()) continue;
        if (m.topology_revision() != mesh.topology_revision() ||
            m.vertices_size() != mesh.vertices_size())
            return false;
        // Properties written (feature edges detected, texture coordinates): a change even
        // where no vertex moves.
        if (m.attribute_revision() != mesh.attribute_revision()) return false;
        if (m.positions() != mesh.positions()) return false;
    }
    return true;
}

}  // namespace

std::shared_ptr<const std::vector<float>> region_of(const Operation& op, const HalfedgeMesh& mesh) {
    if (!op.def || !op.def->takes_region) return nullptr;
    std::optional<Selection> selection = stored_selection(mesh);
    if (!selection || selects_everything(mesh, *selection)) return nullptr;
    return std::make_shared<const std::vector<float>>(std::move(*selection));
}

void SessionDocument::push_loaded(HalfedgeMesh mesh, std::string label, std::string name,
                                  std::string path, LoadReport report) {
    Document& document = core_.document;
    // A load shows no motion: every vertex "starts" where it is.
    MorphCorrespondence none{MorphCorrespondence::Kind::FromEarlier, mesh.positions()};
    // "Load bunny.obj ../meshes/bunny.obj"; the path alone where it is the name.
    const std::string parameters = path == name ? "" : path;
    // The first file replaces the built-in model while nothing was done to it.
    const bool untouched_default =
        document.history.size() == 1 && document.path.empty() && !document.unsaved;
    if (document.history.size() == 0 || untouched_default)
        document.history.reset(std::move(mesh), std::move(label), parameters);
    else
        core_.log_history_messages(document.history.push(std::move(label), parameters, 0.0,
                                                         {std::move(mesh)}, {std::move(none)}));
    document.name = std::move(name);
    document.path = std::move(path);
    document.report = std::move(report);
    core_.state_changed(true);
    document.unsaved = false;
}

void SessionDocument::describe_state() {
    Document& document = core_.document;
    document.unsaved = true;
    const HalfedgeMesh& mesh = document.mesh();
    document.texcoords_projected =
        mesh.has_vertex_property("v:texcoord") && document.texcoords_projected;
    auto components = std::make_shared<std::vector<Index>>();
    const MeshStats s = compute_stats(mesh, components.get());
    document.components = std::move(components);
    document.components_topology = mesh.topology_revision();
    document.closed = s.volume.has_value();
    document.open_seams = s.boundary_loops > 0 && pair_boundary_edges(mesh).paired_edges > 0;
    document.area = s.area;
    char buf[256];
    std::vector<std::string>& info = document.info;
    info.clear();
    info.push_back("model: " + document.name +
                   (document.path.empty() ? "" : " (" + document.path + ")"));
    const History::EntryInfo entry = document.history.info(document.history.current());
    info.push_back("state " + std::to_string(document.history.current()) + " of " +
                   std::to_string(document.history.size()) + ": " + entry.label +
                   (entry.parameters.empty() ? "" : " " + entry.parameters));
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
    for (const std::string& line : document.report.lines()) info.push_back("load: " + line);
}

void SessionDocument::step_history(const Command& command) {
    History& h = core_.document.history;
    if (core_.jobs.busy()) return core_.busy_error();
    if (std::holds_alternative<Undo>(command) && h.can_undo())
        h.undo();
    else if (std::holds_alternative<Redo>(command) && h.can_redo())
        h.redo();
    else if (auto* jump = std::get_if<JumpTo>(&command); jump && jump->entry < h.size())
        h.jump(jump->entry);
    else
        return;
    core_.log.info("now at state " + std::to_string(h.current()) + ": " +
                   h.info(h.current()).label);
    core_.state_changed(false);
}

void SessionDocument::run(const Operation& op) {
    try {
        check_operation(op);
    } catch (const std::exception& e) {
        core_.notify_error(e.what());
        return;
    }
    const HalfedgeMesh snapshot = core_.mesh();  // copy-on-write: the job's own
    const HalfedgeMesh::Revision base = snapshot.revision();
    const auto region = region_of(op, snapshot);
    // The state's components, when the run has a region (a flip then need not find them).
    const Document& document = core_.document;
    const std::shared_ptr<const std::vector<Index>> components =
        region && document.components_topology == snapshot.topology_revision() ? document.components
                                                                               : nullptr;
    const bool started = core_.jobs.start(
        op.text(), [this, op, snapshot, base, region, components](Progress& progress) {
            RunSettings settings;
            settings.region = region.get();
            settings.components = components.get();
            auto result =
                std::make_shared<OperationResult>(run_operation(op, snapshot, progress, settings));
            return JobRunner::Finish([this, result, op, base] {
                // The result belongs to the state it was computed on: never stacked on another.
                if (core_.mesh().revision() != base) {
                    core_.notify_error(result->label +
                                       ": the document changed while it ran; its result is not "
                                       "applied");
                    return;
                }
                commit(op, std::move(*result));
            });
        });
    if (!started) core_.busy_error();
}

void SessionDocument::commit(const Operation& op, OperationResult result) {
    if (!result.changed) {  // stopped before its first good iteration: nothing to keep
        for (const std::string& line : result.report) core_.log.info("  " + line);
        core_.notify_error(result.label + " stopped early, nothing changed: " + result.stop_reason);
        return;
    }
    // A run that changed nothing (a step of 0, no edge to weld) adds no entry, and says so.
    if (leaves_unchanged(core_.mesh(), result)) {
        for (const std::string& line : result.report) core_.log.info("  " + line);
        const std::string text =
            result.label + " " + result.parameters + " changed nothing: no history entry";
        core_.log.info(text);
        core_.inform(text);
        return;
    }
    std::vector<HalfedgeMesh> meshes;
    std::vector<MorphCorrespondence> correspondences;
    for (OperationStep& step : result.steps) {
        meshes.push_back(std::move(step.mesh));
        correspondences.push_back(std::move(step.correspondence));
    }
    core_.log_history_messages(core_.document.history.push(result.label, result.parameters,
                                                           result.ms, std::move(meshes),
                                                           std::move(correspondences), op));
    core_.log.info(result.label + " " + result.parameters);
    for (const std::string& line : result.report) core_.log.info("  " + line);
    core_.state_changed(false);
    if (is_operation<FlipOptions>(op)) {  // replaces a load's "its faces point inwards"
        std::string text = result.label;
        for (std::size_t i = 0; i < result.report.size(); ++i)
            text += (i ? "; " : ": ") + result.report[i];
        core_.inform(text);
    }
    // A run that stopped early keeps its good steps and says why, never silently.
    if (result.stopped_early)
        core_.notify_error(result.label + " stopped early: " + result.stop_reason);
    // Show the change: play the morph once from before to after.
    MorphState& morph = core_.morph;
    morph.t = 0.0;
    morph.playing = true;
    morph.playback = Playback::Once;
    morph.play_start = core_.now();
}

void SessionDocument::project_texcoords(TexCoordProjection projection, UpAxis up) {
    if (core_.jobs.busy()) return core_.busy_error();
    HalfedgeMesh textured = core_.mesh();
    trilab::project_texcoords(textured, projection, up);
    const bool planar = projection == TexCoordProjection::Planar;
    const std::string kind =
        planar ? "planar" : std::string("spherical, +") + up_axis_name(up) + " up";
    // An entry of its own, so it can be undone; the shape does not move.
    core_.document.texcoords_projected = true;
    core_.push_entry("Texture coordinates", kind, 0.0, {std::move(textured)},
                     {MorphCorrespondence{}});
    core_.log.info(kind + " texture coordinates computed on the current shape");
}

std::vector<Point> SessionDocument::reference_positions() const {
    // The state before the current entry, on the current connectivity: the morph's start.
    const History& history = core_.document.history;
    if (history.size() == 0 || history.current() == 0) return {};
    try {
        MorphFrame start = history.morph(history.current(), 0.0);
        if (start.topology && start.positions.size() == core_.mesh().vertices_size())
            return std::move(start.positions);
    } catch (const std::exception&) {
        // No usable earlier state: the colouring says so.
    }
    return {};
}

bool SessionDocument::entry_moves() const {
    const History& h = core_.document.history;
    const std::size_t entry = h.current();
    if (h.size() == 0 || entry == 0) return false;
    const History::EntryInfo info = h.info(entry);
    // Operations move vertices; a state the session made itself (a load, a revert, texture
    // coordinates) may not: compare its start with its end.
    if (info.operation.def || info.steps.size() != 1) return true;
    try {
        const MorphFrame start = h.morph(entry, 0.0);
        const HalfedgeMesh& mesh = core_.mesh();
        if (!start.topology || start.positions.size() != mesh.vertices_size()) return true;
        for (Vertex v : mesh.vertices())
            if (start.positions[v.idx()] != mesh.position(v)) return true;
    } catch (const std::exception&) {
        return true;
    }
    return false;
}

}  // namespace trilab::viewer
