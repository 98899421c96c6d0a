#include "core/algorithms/texcoords.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/errors.h"

namespace trilab {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// The live vertices; throws InvalidArgument (before anything changes) on a non-finite
/// position.
std::vector<Vertex> live_vertices(const HalfedgeMesh& mesh) {
    std::vector<Vertex> vs;
    vs.reserve(mesh.n_vertices());
    for (Vertex v : mesh.vertices()) {
        if (!mesh.position(v).allFinite())
            throw InvalidArgument("project_texcoords: vertex " + std::to_string(v.idx()) +
                                  " has a non-finite position");
        vs.push_back(v);
    }
    return vs;
}

Point centroid(const HalfedgeMesh& mesh, const std::vector<Vertex>& vs) {
    Point c = Point::Zero();
    for (Vertex v : vs) c += mesh.position(v);
    return vs.empty() ? c : Point(c / double(vs.size()));
}

/// `axis` with the sign that makes its largest-magnitude component positive.
Vector3 canonical_sign(const Vector3& axis) {
    Eigen::Index k = 0;
    axis.cwiseAbs().maxCoeff(&k);
    return axis[k] < 0 ? Vector3(-axis) : axis;
}

/// The coordinate axis most nearly perpendicular to `n`, made exactly perpendicular.
Vector3 axis_perpendicular_to(const Vector3& n) {
    Eigen::Index k = 0;
    n.cwiseAbs().minCoeff(&k);
    Vector3 a = Vector3::Unit(k);
    return (a - a.dot(n) * n).normalized();
}

/// The projection frame: `u` along the largest principal axis, `n` along the smallest,
/// v = n x u. Where eigenvalues tie (a square, a disc, a sphere) the principal axes are
/// arbitrary, so coordinate axes break the tie, which keeps axis-aligned shapes
/// axis-aligned. `n` points to the side the faces face, so the texture is not mirrored when
/// seen from the front.
void planar_frame(const HalfedgeMesh& mesh, const std::vector<Vertex>& vs, const Point& c,
                  Vector3& u, Vector3& v) {
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (Vertex x : vs) {
        const Vector3 d = mesh.position(x) - c;
        cov += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    const Vector3 lambda = eig.eigenvalues();  // ascending
    const Eigen::Matrix3d axes = eig.eigenvectors();
    const double tie = 1e-9 * std::max(lambda[2], 0.0);
    Vector3 n;
    if (lambda[2] - lambda[0] <= tie) {  // isotropic: project along z
        n = Vector3::UnitZ();
        u = Vector3::UnitX();
    } else if (lambda[2] - lambda[1] <= tie) {  // the two largest tie: the plane is known
        n = axes.col(0).normalized();
        u = axis_perpendicular_to(n);
    } else if (lambda[1] - lambda[0] <= tie) {  // the two smallest tie: only u is known
        u = axes.col(2).normalized();
        n = u.cross(axis_perpendicular_to(u)).normalized();
    } else {
        u = axes.col(2).normalized();
        n = axes.col(0).normalized();
    }
    // The vector area (zero for a closed mesh) says which side the faces face.
    Vector3 area = Vector3::Zero();
    double total_area = 0;
    for (Face f : mesh.faces()) {
        const auto p = mesh.face_vertices(f);
        const Vector3 a = (mesh.position(p[1]) - mesh.position(p[0]))
                              .cross(mesh.position(p[2]) - mesh.position(p[0]));
        area += a;
        total_area += a.norm();
    }
    const double facing = area.dot(n);
    if (std::abs(facing) > 1e-9 * total_area)
        n = facing < 0 ? Vector3(-n) : n;
    else
        n = canonical_sign(n);
    u = canonical_sign(u);
    v = n.cross(u).normalized();
}

void project_planar(const HalfedgeMesh& mesh, const std::vector<Vertex>& vs,
                    std::vector<TexCoord>& uv) {
    const Point c = centroid(mesh, vs);
    Vector3 u_axis, v_axis;
    planar_frame(mesh, vs, c, u_axis, v_axis);
    TexCoord lo = TexCoord::Constant(std::numeric_limits<double>::infinity());
    TexCoord hi = -lo;
    for (std::size_t i = 0; i < vs.size(); ++i) {
        const Vector3 d = mesh.position(vs[i]) - c;
        uv[i] = TexCoord(d.dot(u_axis), d.dot(v_axis));
        lo = lo.cwiseMin(uv[i]);
        hi = hi.cwiseMax(uv[i]);
    }
    const double extent = (hi - lo).maxCoeff();
    const double scale = extent > 0 ? 1.0 / extent : 0.0;
    for (TexCoord& t : uv)
        t = ((t - lo) * scale).cwiseMax(0.0).cwiseMin(1.0);  // clamp rounding only
}

void project_spherical(const HalfedgeMesh& mesh, const std::vector<Vertex>& vs, UpAxis up,
                       std::vector<TexCoord>& uv) {
    const Point c = centroid(mesh, vs);
    // The frame of the up axis (core/up_axis.h): longitude 0 faces the front, the seam is at
    // the back; for y-up (right, front, up) = (x, z, y), for z-up (x, -y, z).
    const Vector3 up_axis = up_vector(up), front = front_vector(up);
    const Vector3 right = up_axis.cross(front);
    for (std::size_t i = 0; i < vs.size(); ++i) {
        const Vector3 d = mesh.position(vs[i]) - c;
        const double a = d.dot(right), b = d.dot(front), h = d.dot(up_axis);
        const double r_horizontal = std::hypot(a, b);
        // On the axis (the poles, and the centre itself) longitude is undefined: take 0.
        const double longitude = r_horizontal > 1e-12 * d.norm() ? std::atan2(a, b) : 0.0;
        const double latitude = d.norm() > 0 ? std::atan2(h, r_horizontal) : 0.0;
        uv[i] = TexCoord(std::clamp(longitude / (2 * kPi) + 0.5, 0.0, 1.0),
                         std::clamp(latitude / kPi + 0.5, 0.0, 1.0));
    }
}

}  // namespace

bool has_texcoords(const HalfedgeMesh& mesh) {
    return bool(mesh.get_vertex_property<TexCoord>("v:texcoord")) ||
           bool(mesh.get_halfedge_property<TexCoord>("h:texcoord"));
}

void project_texcoords(HalfedgeMesh& mesh, TexCoordProjection projection, UpAxis up) {
    const std::vector<Vertex> vs = live_vertices(mesh);
    std::vector<TexCoord> uv(vs.size(), TexCoord::Zero());
    switch (projection) {
        case TexCoordProjection::Planar:
            project_planar(mesh, vs, uv);
            break;
        case TexCoordProjection::Spherical:
            project_spherical(mesh, vs, up, uv);
            break;
        default:
            throw InvalidArgument("project_texcoords: unknown projection");
    }
    // A "v:texcoord" of another type is replaced.
    if (mesh.has_vertex_property("v:texcoord") && !mesh.get_vertex_property<TexCoord>("v:texcoord"))
        mesh.remove_vertex_property("v:texcoord");
    auto prop = mesh.vertex_property<TexCoord>("v:texcoord");
    for (std::size_t i = 0; i < vs.size(); ++i) prop[vs[i]] = uv[i];
}

bool on_texture_seam(const HalfedgeMesh& mesh, const HalfedgeProperty<const TexCoord>& corner_uv,
                     Vertex v) {
    if (!corner_uv || mesh.is_isolated(v)) return false;
    bool have = false;
    TexCoord uv = TexCoord::Zero();
    for (Halfedge g : mesh.halfedges_around(v)) {
        const Halfedge in = HalfedgeMesh::twin(g);
        if (mesh.is_boundary(in)) continue;
        if (!have) {
            uv = corner_uv[in];
            have = true;
        } else if (corner_uv[in] != uv) {
            return true;
        }
    }
    return false;
}

}  // namespace trilab
