// The session's picks and measurements; see session_picking.h.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <utility>

#include "app/session/session_picking.h"
#include "core/algorithms/geodesic.h"
#include "core/errors.h"

namespace trilab::viewer {
namespace {

std::string format_distance(double d) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.6g", d);
    return buf;
}

}  // namespace

void SessionPicking::pick(const Ray& ray, double t_min, bool second) {
    const Shown& shown = core_.shown;
    std::optional<Pick> hit;
    try {
        hit = pick_shown(shown, core_.mesh(), ray, t_min);
    } catch (const std::exception& e) {
        core_.notify_error(std::string("pick: ") + e.what());
        return;
    }
    if (!hit) {
        clear();
        return;
    }
    // The mesh the indices refer to: the shown mesh (a morph frame with its positions), or
    // the document on a level of detail.
    HalfedgeMesh mesh = hit->on_level || !shown.mesh ? core_.mesh() : *shown.mesh;
    if (!hit->on_level && shown.positions.size() == mesh.vertices_size() &&
        shown.kind == Shown::Kind::Morph)
        mesh.set_positions(shown.positions);
    const bool same_state = !picks_.picks.empty() &&
                            picks_.mesh.topology_revision() == mesh.topology_revision() &&
                            picks_.mesh.geometry_revision() == mesh.geometry_revision();
    if (second && same_state) {
        picks_.picks.resize(1);
        picks_.picks.push_back(*hit);
    } else {
        picks_.picks = {*hit};
        if (!same_state) picks_.mesh = std::move(mesh);
    }
    core_.log.info("picked " + pick_line(*hit));
    restart(true);
}

void SessionPicking::restart(bool measure) {
    picks_.measurement = Measurement{};
    picks_.distances.clear();
    job_pending_ = false;
    ++request_;
    ++picks_.version;
    if (!measure) return;
    if (picks_.picks.size() == 2) {
        const HalfedgeMesh& mesh = picks_.mesh;
        picks_.measurement.straight =
            (mesh.position(picks_.picks[0].vertex) - mesh.position(picks_.picks[1].vertex)).norm();
        picks_.measurement.computing = true;
    }
    job_pending_ = picks_.picks.size() == 2 || want_distances_;
    start_job();
    start_inspection();
}

void SessionPicking::clear() {
    if (picks_.picks.empty()) return;
    picks_.picks.clear();
    restart(false);
}

void SessionPicking::want_distances(bool want) {
    if (want == want_distances_) return;
    want_distances_ = want;
    if (want && !picks_.picks.empty() && picks_.distances.empty()) {
        job_pending_ = true;
        ++request_;
        start_job();
    }
}

void SessionPicking::follow() {
    if (picks_.picks.empty()) return;
    const HalfedgeMesh& doc = core_.mesh();
    if (doc.topology_revision() == picks_.mesh.topology_revision() &&
        doc.geometry_revision() == picks_.mesh.geometry_revision())
        return;  // the same shape (attributes aside)
    if (doc.topology_revision() != picks_.mesh.topology_revision() ||
        doc.vertices_size() != picks_.mesh.vertices_size()) {
        picks_.picks.clear();
        picks_.mesh = HalfedgeMesh();
        restart(false);
        core_.log.info("picks dropped: this state has other vertices and faces (renumbered)");
        core_.inform("picks dropped: this state's vertices and faces are numbered anew");
        return;
    }
    // A geometry-only step: the same elements, moved. Hits follow their faces.
    picks_.mesh = doc;
    for (Pick& p : picks_.picks) {
        p.position = Point::Zero();
        for (int k = 0; k < 3; ++k) p.position += p.barycentric[k] * doc.position(p.corners[k]);
    }
    restart(true);
}

void SessionPicking::update() {
    start_job();
    take_inspection();
}

void SessionPicking::set_inspection_options(const DecimationOptions& options) {
    const DecimationOptions& o = inspection_options_;
    if (o.cost == options.cost && o.min_roundness == options.min_roundness &&
        o.max_normal_angle == options.max_normal_angle && o.max_error == options.max_error &&
        o.independent_set == options.independent_set && o.roundness == options.roundness &&
        o.normal_flip == options.normal_flip)
        return;
    inspection_options_ = options;
    if (!picks_.picks.empty()) start_inspection();
}

void SessionPicking::start_inspection() {
    picks_.inspection.reset();
    if (picks_.picks.empty()) return;
    // A running inspection finishes first (its result is stale then and dropped):
    // take_inspection() starts this one when it has ended, so the frame never waits for it.
    inspection_pending_ = true;
    if (!inspection_future_.valid()) launch_inspection();
}

void SessionPicking::launch_inspection() {
    inspection_pending_ = false;
    const HalfedgeMesh snapshot = picks_.mesh;  // copy-on-write: the worker's own
    const Pick pick = picks_.picks.front();
    const DecimationOptions options = inspection_options_;
    auto reference = std::make_shared<const std::vector<Point>>(document_.reference_positions());
    inspection_request_ = request_;
    inspection_future_ = std::async(std::launch::async, [snapshot, pick, options, reference] {
        auto out = std::make_shared<PickInspection>();
        const auto t0 = std::chrono::steady_clock::now();
        try {
            InspectionInputs inputs;
            if (reference->size() == snapshot.vertices_size()) inputs.reference = reference.get();
            if (snapshot.is_valid(pick.vertex) && !snapshot.is_deleted(pick.vertex))
                out->vertex = inspect_vertex(snapshot, pick.vertex, inputs);
            if (pick.edge.is_valid() && snapshot.is_valid(pick.edge) &&
                !snapshot.is_deleted(pick.edge))
                out->edge = inspect_edge(snapshot, pick.edge, options);
            if (pick.face.is_valid() && snapshot.is_valid(pick.face) &&
                !snapshot.is_deleted(pick.face))
                out->face = inspect_face(snapshot, pick.face);
        } catch (const std::exception& e) {
            out->failure = e.what();
        }
        out->ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                      .count();
        return std::shared_ptr<const PickInspection>(out);
    });
}

void SessionPicking::take_inspection() {
    if (!inspection_future_.valid() ||
        inspection_future_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
        return;
    std::shared_ptr<const PickInspection> result = inspection_future_.get();
    if (inspection_pending_ && !picks_.picks.empty()) {  // picked again meanwhile: its turn
        launch_inspection();
        return;
    }
    if (inspection_request_ != request_ || picks_.picks.empty()) return;  // stale
    if (!result->failure.empty()) core_.log.warning("inspector: " + result->failure);
    picks_.inspection = std::move(result);
    ++picks_.version;
}

void SessionPicking::finish_inspection() {
    while (inspection_future_.valid()) {
        inspection_future_.wait();
        take_inspection();
    }
}

void SessionPicking::start_job() {
    if (!job_pending_ || core_.jobs.busy() || picks_.picks.empty()) return;
    job_pending_ = false;
    struct Result {
        std::shared_ptr<const GeodesicSolver> solver;
        Measurement measurement;
        std::vector<double> distances;
        std::string failure;
    };
    const HalfedgeMesh snapshot = picks_.mesh;  // copy-on-write: the job's own
    const HalfedgeMesh::Revision state = snapshot.revision();
    std::shared_ptr<const GeodesicSolver> cached =
        picks_.solver && picks_.solver_state == state ? picks_.solver : nullptr;
    const std::vector<Pick> picks = picks_.picks;
    const bool want_distances = want_distances_;
    const Measurement start = picks_.measurement;
    const std::uint64_t request = request_;
    const bool started = core_.jobs.start("Geodesic distance", [=](Progress&) {
        auto result = std::make_shared<Result>();
        result->measurement = start;
        const auto t0 = std::chrono::steady_clock::now();
        try {
            result->solver = cached ? cached : std::make_shared<const GeodesicSolver>(snapshot);
            if (picks.size() == 2) {
                const std::vector<double> from_a = result->solver->distances({picks[0].vertex});
                const double d = from_a[picks[1].vertex.idx()];
                result->measurement.geodesic = d;
                if (std::isfinite(d)) {
                    const std::vector<SurfacePoint> path =
                        geodesic_path(snapshot, from_a, picks[1].vertex);
                    result->measurement.path_length = path_length(path);
                    for (const SurfacePoint& p : path)
                        result->measurement.path.push_back(p.position);
                } else {
                    result->measurement.failure =
                        "the two picks are on separate components: no path on the surface";
                }
            }
            if (want_distances) {
                std::vector<Vertex> sources;
                for (const Pick& p : picks) sources.push_back(p.vertex);
                result->distances = result->solver->distances(sources);
            }
        } catch (const std::exception& e) {
            result->failure = e.what();
            result->measurement.failure = e.what();
        }
        result->measurement.computing = false;
        result->measurement.ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count();
        return JobRunner::Finish([this, result, state, request] {
            if (request != request_) return;  // picks changed meanwhile: stale
            if (result->solver) {
                picks_.solver = result->solver;
                picks_.solver_state = state;
            }
            picks_.measurement = result->measurement;
            picks_.distances = std::move(result->distances);
            ++picks_.version;
            if (!result->failure.empty()) {
                core_.log.warning("geodesic distance: " + result->failure);
            } else if (picks_.picks.size() == 2) {
                core_.log.info("measure: straight " + format_distance(picks_.measurement.straight) +
                               " geodesic " + format_distance(picks_.measurement.geodesic) +
                               " path points " + std::to_string(picks_.measurement.path.size()));
            }
        });
    });
    if (!started) job_pending_ = true;  // the runner is busy: start when it is free
}

}  // namespace trilab::viewer
