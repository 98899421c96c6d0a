// The brush and the lasso on the screen; see screen_selection.h.
#include "app/session/screen_selection.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace trilab::viewer {
namespace {

/// A projected point: pixel x, y and its depth (clip w: the distance along the view axis).
struct ScreenPoint {
    double x = 0, y = 0, w = 0;
};

ScreenPoint project(const ScreenView& view, const Point& p) {
    const Eigen::Vector4d c = view.view_projection * Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0);
    ScreenPoint s;
    s.w = c.w();
    if (!(c.w() > 0)) return s;
    s.x = (c.x() / c.w() * 0.5 + 0.5) * view.width;
    s.y = (0.5 - c.y() / c.w() * 0.5) * view.height;
    return s;
}

/// The nearest depth per pixel over the triangles in front of the camera (a CPU z-buffer of
/// 1/w, which is linear on the screen).
class DepthBuffer {
public:
    DepthBuffer(int width, int height)
        : width_(width), height_(height), inverse_(std::size_t(width) * height, 0.0f) {}

    void add(const ScreenPoint& a, const ScreenPoint& b, const ScreenPoint& c) {
        const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        if (!(std::abs(area) > 1e-12)) return;
        const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
        const int x1 = std::min(width_ - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
        const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
        const int y1 = std::min(height_ - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
        const double ia = 1.0 / a.w, ib = 1.0 / b.w, ic = 1.0 / c.w;
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const double px = x + 0.5, py = y + 0.5;
                const double l0 = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) / area;
                const double l1 = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
                const double l2 = 1.0 - l0 - l1;
                if (l0 < 0 || l1 < 0 || l2 < 0) continue;
                float& d = inverse_[std::size_t(y) * width_ + x];
                d = std::max(d, float(l0 * ia + l1 * ib + l2 * ic));
            }
    }
    /// The nearest depth at the pixel of (x, y); infinity where nothing was drawn.
    double depth(double x, double y) const {
        const int px = int(std::floor(x)), py = int(std::floor(y));
        if (px < 0 || py < 0 || px >= width_ || py >= height_)
            return std::numeric_limits<double>::infinity();
        const float inv = inverse_[std::size_t(py) * width_ + px];
        return inv > 0 ? 1.0 / inv : std::numeric_limits<double>::infinity();
    }

private:
    int width_, height_;
    std::vector<float> inverse_;
};

float distance_to_segment(const Eigen::Vector2f& p, const Eigen::Vector2f& a,
                          const Eigen::Vector2f& b) {
    const Eigen::Vector2f ab = b - a;
    const float len2 = ab.squaredNorm();
    const float t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0f, 1.0f) : 0.0f;
    return (p - (a + t * ab)).norm();
}

}  // namespace

ProjectedVertices project_vertices(const HalfedgeMesh& mesh, const std::vector<Point>& positions,
                                   const ScreenView& view, bool through) {
    const std::size_t n = mesh.vertices_size();
    ProjectedVertices out;
    out.pixel.assign(n, Eigen::Vector2f::Zero());
    out.eligible.assign(n, 0);
    std::vector<ScreenPoint> screen(n);
    Eigen::AlignedBox3d box;
    for (Vertex v : mesh.vertices()) {
        const Point& p = positions[v.idx()];
        box.extend(p);
        screen[v.idx()] = project(view, p);
        out.pixel[v.idx()] = Eigen::Vector2f(float(screen[v.idx()].x), float(screen[v.idx()].y));
        out.eligible[v.idx()] = screen[v.idx()].w > 0 ? 1 : 0;
    }
    if (through || mesh.n_faces() == 0) return out;
    const int width = std::clamp(int(std::ceil(view.width)), 1, 16384);
    const int height = std::clamp(int(std::ceil(view.height)), 1, 16384);
    DepthBuffer depth(width, height);
    for (Face f : mesh.faces()) {
        // A fan over the face's corners (the mesh is triangulated; polygons are fans).
        Halfedge h0 = mesh.halfedge(f);
        const Vertex v0 = mesh.to_vertex(h0);
        Halfedge h = mesh.next(h0);
        for (; mesh.next(h) != h0; h = mesh.next(h)) {
            const Vertex v1 = mesh.to_vertex(h), v2 = mesh.to_vertex(mesh.next(h));
            const ScreenPoint &a = screen[v0.idx()], &b = screen[v1.idx()], &c = screen[v2.idx()];
            if (a.w > 0 && b.w > 0 && c.w > 0) depth.add(a, b, c);
        }
    }
    const double tolerance = 0.01 * (box.isEmpty() ? 0.0 : box.diagonal().norm());
    for (Vertex v : mesh.vertices()) {
        const ScreenPoint& s = screen[v.idx()];
        if (out.eligible[v.idx()] && s.w > depth.depth(s.x, s.y) + tolerance)
            out.eligible[v.idx()] = 0;
    }
    return out;
}

std::size_t paint_brush(const ProjectedVertices& projected, const Eigen::Vector2f& a,
                        const Eigen::Vector2f& b, float radius, bool add, Selection& weights) {
    const float value = add ? 1.0f : 0.0f;
    const Eigen::Vector2f lo = a.cwiseMin(b).array() - radius, hi = a.cwiseMax(b).array() + radius;
    std::size_t changed = 0;
    const std::size_t n = std::min(weights.size(), projected.pixel.size());
    for (std::size_t i = 0; i < n; ++i) {
        if (!projected.eligible[i] || weights[i] == value) continue;
        const Eigen::Vector2f& p = projected.pixel[i];
        if (p.x() < lo.x() || p.y() < lo.y() || p.x() > hi.x() || p.y() > hi.y()) continue;
        if (distance_to_segment(p, a, b) > radius) continue;
        weights[i] = value;
        ++changed;
    }
    return changed;
}

Selection lasso_selection(const ProjectedVertices& projected,
                          const std::vector<Eigen::Vector2f>& lasso) {
    Selection out(projected.pixel.size(), 0.0f);
    if (lasso.size() < 3) return out;
    Eigen::Vector2f lo = lasso[0], hi = lasso[0];
    for (const Eigen::Vector2f& q : lasso) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (!projected.eligible[i]) continue;
        const Eigen::Vector2f& p = projected.pixel[i];
        if (p.x() < lo.x() || p.y() < lo.y() || p.x() > hi.x() || p.y() > hi.y()) continue;
        bool inside = false;
        for (std::size_t k = 0, j = lasso.size() - 1; k < lasso.size(); j = k++) {
            const Eigen::Vector2f &u = lasso[k], &w = lasso[j];
            if ((u.y() > p.y()) != (w.y() > p.y()) &&
                p.x() < (w.x() - u.x()) * (p.y() - u.y()) / (w.y() - u.y()) + u.x())
                inside = !inside;
        }
        if (inside) out[i] = 1.0f;
    }
    return out;
}

}  // namespace trilab::viewer
