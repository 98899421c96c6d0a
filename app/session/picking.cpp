// Picking the shown surface (app/session/picking.h).
#include "app/session/picking.h"

#include <chrono>
#include <cstdio>

#include "app/session/session.h"
#include "core/algorithms/level_of_detail.h"

namespace trilab::viewer {

std::string pick_line(const Pick& pick) {
    auto index = [](auto handle) {
        return handle.is_valid() ? std::to_string(handle.idx()) : std::string("-");
    };
    char buf[160];
    std::snprintf(buf, sizeof buf, " position %.9g %.9g %.9g ms %.2f", pick.position.x(),
                  pick.position.y(), pick.position.z(), pick.ms);
    return "vertex " + index(pick.vertex) + " edge " + index(pick.edge) + " face " +
           index(pick.face) + buf;
}

std::optional<Pick> pick_shown(const Shown& shown, const HalfedgeMesh& document, const Ray& ray,
                               double t_min) {
    const auto start = std::chrono::steady_clock::now();
    Pick pick;
    if (shown.kind == Shown::Kind::Level && shown.level) {
        const LevelOfDetail& lod = *shown.level;
        const auto hit = pick_triangle(lod.faces(), lod.face_alive(), lod.positions(), ray, t_min);
        if (!hit) return std::nullopt;
        // The level's faces are the fine mesh's faces in the level's drawing order, and its
        // vertices the fine mesh's (document) vertices: map both back.
        for (int k = 0; k < 3; ++k) pick.corners[k] = Vertex(lod.fine_vertex(hit->corners[k]));
        pick.vertex = pick.corners[hit->nearest_corner];
        pick.edge = document.find_edge(pick.corners[hit->nearest_edge],
                                       pick.corners[(hit->nearest_edge + 1) % 3]);
        for (Face f : document.faces())
            if (lod.face_of(f.idx()) == hit->triangle) {
                pick.face = f;
                break;
            }
        pick.barycentric = hit->barycentric;
        pick.position = hit->position;
        pick.back_face = hit->back_face;
        pick.on_level = true;
    } else {
        if (!shown.mesh) return std::nullopt;
        const HalfedgeMesh& mesh = *shown.mesh;
        const std::vector<Point>& positions =
            shown.positions.size() == mesh.vertices_size() ? shown.positions : mesh.positions();
        const auto hit = pick_face(mesh, positions, ray, t_min);
        if (!hit) return std::nullopt;
        for (int k = 0; k < 3; ++k) pick.corners[k] = Vertex(hit->corners[k]);
        pick.face = Face(hit->triangle);
        pick.vertex = pick.corners[hit->nearest_corner];
        pick.edge = HalfedgeMesh::edge(face_side(mesh, pick.face, hit->nearest_edge));
        pick.barycentric = hit->barycentric;
        pick.position = hit->position;
        pick.back_face = hit->back_face;
    }
    pick.ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return pick;
}

}  // namespace trilab::viewer
