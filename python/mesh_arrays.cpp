// trilab.Mesh's arrays: V (a read-only view of the mesh's own positions), F, the vertex
// properties, the constructor from (V, F) arrays of any dtype and memory order, and the
// analyses that return arrays (spectrum, laplacian, geodesic).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/algorithms/coloring.h"
#include "core/algorithms/geodesic.h"
#include "core/algorithms/inspect.h"
#include "core/algorithms/laplacian.h"
#include "core/algorithms/spectral.h"
#include "core/errors.h"
#include "core/mesh_builder.h"
#include "python/mesh_handle.h"

namespace py = pybind11;

namespace trilab::python {

std::shared_ptr<MeshHandle> make_handle(HalfedgeMesh mesh) {
    auto h = std::make_shared<MeshHandle>();
    h->mesh = std::move(mesh);
    if (h->mesh.has_garbage()) h->mesh.garbage_collection();
    return h;
}

namespace {

static_assert(sizeof(Point) == 3 * sizeof(double), "Mesh.V views Points as 3 doubles");

/// V: the positions array itself, read-only, kept alive by the Mesh (its base).
py::array positions_view(const py::object& self) {
    const MeshHandle& h = self.cast<const MeshHandle&>();
    const std::vector<Point>& p = h.mesh.positions();  // const: never unshares (copies)
    const auto n = static_cast<py::ssize_t>(p.size());
    static const double kNone[3] = {0, 0, 0};
    const double* data = n ? p.front().data() : kNone;
    py::array_t<double> a({n, py::ssize_t(3)},
                          {py::ssize_t(sizeof(Point)), py::ssize_t(sizeof(double))}, data, self);
    py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return py::array(a);
}

/// F: the faces' vertex indices, (m, 3) int64 (a new array).
py::array_t<std::int64_t> face_array(const MeshHandle& h) {
    py::array_t<std::int64_t> f({py::ssize_t(h.mesh.n_faces()), py::ssize_t(3)});
    auto out = f.mutable_unchecked<2>();
    py::ssize_t i = 0;
    for (Face face : h.mesh.faces()) {
        const std::array<Vertex, 3> v = h.mesh.face_vertices(face);
        for (int c = 0; c < 3; ++c) out(i, c) = std::int64_t(v[std::size_t(c)].idx());
        ++i;
    }
    return f;
}

/// A copy of vertex property array `values` as an (n,) or (n, k) array.
template <class T, int K>
py::array property_array(const std::vector<T>& values) {
    using Scalar = std::remove_cv_t<std::remove_reference_t<decltype(values[0][0])>>;
    py::array_t<Scalar> a({py::ssize_t(values.size()), py::ssize_t(K)});
    auto out = a.template mutable_unchecked<2>();
    for (std::size_t i = 0; i < values.size(); ++i)
        for (int c = 0; c < K; ++c) out(py::ssize_t(i), c) = values[i][c];
    return py::array(a);
}

template <class T>
py::array scalar_array(const std::vector<T>& values) {
    return py::array_t<T>(py::ssize_t(values.size()), values.data());
}

/// vertex_property(name): "selection" or "v:selection"; a copy, one row per vertex.
py::array vertex_property(const MeshHandle& h, const std::string& name) {
    const HalfedgeMesh& m = h.mesh;
    for (const std::string& n : {name, "v:" + name}) {
        if (auto p = m.get_vertex_property<double>(n)) return scalar_array(p.vector());
        if (auto p = m.get_vertex_property<float>(n)) return scalar_array(p.vector());
        if (auto p = m.get_vertex_property<std::uint8_t>(n)) return scalar_array(p.vector());
        if (auto p = m.get_vertex_property<std::int32_t>(n)) return scalar_array(p.vector());
        if (auto p = m.get_vertex_property<Index>(n)) return scalar_array(p.vector());
        if (auto p = m.get_vertex_property<Point>(n)) return property_array<Point, 3>(p.vector());
        if (auto p = m.get_vertex_property<Color>(n)) return property_array<Color, 3>(p.vector());
        if (auto p = m.get_vertex_property<TexCoord>(n))
            return property_array<TexCoord, 2>(p.vector());
    }
    std::string names;
    for (const std::string& n : m.vertex_property_names()) names += (names.empty() ? "" : ", ") + n;
    throw py::key_error("vertex_property: no vertex property '" + name +
                        "' of a number or vector type (the mesh has: " + names + ")");
}

std::string shape_text(const py::array& a) {
    std::string s = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
    return s + (a.ndim() == 1 ? ",)" : ")");
}

/// Mesh(V, F): V any real (n, 3), F any integer (m, 3) or real with whole values.
std::vector<Point> positions_from(const py::object& obj) {
    const auto V = py::array_t<double, py::array::forcecast>::ensure(obj);
    if (!V) {
        PyErr_Clear();
        throw InvalidArgument("Mesh: V: expected an (n, 3) array of numbers");
    }
    if (V.ndim() != 2 || V.shape(1) != 3)
        throw InvalidArgument("Mesh: V: expected shape (n, 3), got " + shape_text(V));
    std::vector<Point> p(std::size_t(V.shape(0)));
    const auto a = V.unchecked<2>();
    for (py::ssize_t i = 0; i < V.shape(0); ++i) {
        p[std::size_t(i)] = Point(a(i, 0), a(i, 1), a(i, 2));
        if (!p[std::size_t(i)].allFinite())
            throw InvalidArgument("Mesh: V: vertex " + std::to_string(i) +
                                  " has a non-finite coordinate");
    }
    return p;
}

std::vector<Index> corners_from(const py::object& obj, std::size_t n_vertices) {
    const py::array raw = py::array::ensure(obj);
    if (!raw || raw.ndim() != 2 || raw.shape(1) != 3)
        throw InvalidArgument("Mesh: F: expected an (m, 3) array of vertex indices, got " +
                              (raw ? shape_text(raw) : std::string("no array")));
    const char kind = raw.dtype().kind();
    if (kind != 'i' && kind != 'u' && kind != 'f')
        throw InvalidArgument("Mesh: F: expected integer vertex indices, got dtype " +
                              py::str(raw.dtype()).cast<std::string>());
    const auto F = py::array_t<double, py::array::forcecast>::ensure(raw);
    const auto a = F.unchecked<2>();
    std::vector<Index> corners(std::size_t(F.shape(0)) * 3);
    for (py::ssize_t i = 0; i < F.shape(0); ++i)
        for (py::ssize_t c = 0; c < 3; ++c) {
            const double x = a(i, c);
            const std::string where =
                "Mesh: F: face " + std::to_string(i) + " corner " + std::to_string(c) + ": ";
            if (kind == 'f' && (!std::isfinite(x) || x != std::floor(x)))
                throw InvalidArgument(where + py::repr(py::float_(x)).cast<std::string>() +
                                      " is not a whole number");
            if (x < 0 || x >= double(n_vertices))
                throw InvalidArgument(
                    where + "vertex " + std::to_string(static_cast<long long>(x)) +
                    " is out of range (" + std::to_string(n_vertices) + " vertices)");
            corners[std::size_t(i * 3 + c)] = Index(x);
        }
    return corners;
}

std::shared_ptr<MeshHandle> mesh_from_arrays(const py::object& v, const py::object& f) {
    PolygonSoup soup;
    soup.positions = positions_from(v);
    soup.corners = corners_from(f, soup.positions.size());
    soup.face_offsets.resize(soup.corners.size() / 3 + 1);
    for (std::size_t i = 0; i < soup.face_offsets.size(); ++i) soup.face_offsets[i] = 3 * i;
    LoadReport report;
    HalfedgeMesh mesh;
    {
        py::gil_scoped_release release;
        check_polygon_soup(soup);
        mesh = build_mesh(std::move(soup), report);
    }
    std::shared_ptr<MeshHandle> h = make_handle(std::move(mesh));
    h->load_report = report.lines();
    return h;
}

/// A (rows x cols) matrix over the mesh's rows as an (n_vertices, cols) array (isolated
/// vertices, which have no row, get zeros).
py::array_t<double> per_vertex(const HalfedgeMesh& mesh, const VertexIndexMap& map,
                               const Eigen::MatrixXd& x) {
    py::array_t<double> a({py::ssize_t(mesh.vertices_size()), py::ssize_t(x.cols())});
    auto out = a.mutable_unchecked<2>();
    for (py::ssize_t i = 0; i < a.shape(0); ++i)
        for (py::ssize_t c = 0; c < a.shape(1); ++c) out(i, c) = 0;
    for (std::size_t r = 0; r < map.rows(); ++r)
        for (Eigen::Index c = 0; c < x.cols(); ++c)
            out(py::ssize_t(map.vertex_of[r].idx()), c) = x(Eigen::Index(r), c);
    return a;
}

py::tuple spectrum(const MeshHandle& h, std::size_t k, const std::string& op,
                   const std::string& mass, bool fix_boundary, const std::string& end) {
    SpectralOptions o;
    o.k = k;
    o.op = parse_laplacian_operator(op);
    o.mass = parse_mass_matrix(mass);
    o.fix_boundary = fix_boundary;
    o.end = parse_spectrum_end(end);
    SpectralDecomposition d;
    {
        py::gil_scoped_release release;
        d = decompose(h.mesh, o);
    }
    py::array_t<double> values(py::ssize_t(d.eigenvalues.size()), d.eigenvalues.data());
    return py::make_tuple(values, per_vertex(h.mesh, d.map, d.eigenvectors));
}

/// K (or L = -S⁻¹K with normalized=True) over every vertex, as scipy.sparse.csr_matrix.
py::object laplacian(const MeshHandle& h, const std::string& op, const std::string& mass,
                     bool fix_boundary, bool normalized) {
    const py::module_ sparse = py::module_::import("scipy.sparse");  // ImportError without SciPy
    LaplacianOptions o;
    o.mass = parse_mass_matrix(mass);
    o.fix_boundary = fix_boundary;
    const Laplacian lap = build_laplacian(h.mesh, parse_laplacian_operator(op), o);
    const SparseMatrix& M = normalized ? lap.L : lap.K;
    std::vector<std::int64_t> rows, cols;
    std::vector<double> values;
    for (Eigen::Index c = 0; c < M.outerSize(); ++c)
        for (SparseMatrix::InnerIterator it(M, c); it; ++it) {
            rows.push_back(lap.map.vertex_of[std::size_t(it.row())].idx());
            cols.push_back(lap.map.vertex_of[std::size_t(it.col())].idx());
            values.push_back(it.value());
        }
    const auto n = py::ssize_t(h.mesh.vertices_size());
    const py::object coo = sparse.attr("coo_matrix")(
        py::make_tuple(py::array(py::cast(values)),
                       py::make_tuple(py::array(py::cast(rows)), py::array(py::cast(cols)))),
        py::make_tuple(n, n));
    return coo.attr("tocsr")();
}

py::array_t<double> geodesic(const MeshHandle& h, const std::vector<long long>& sources,
                             const std::string& mass, double time_factor) {
    std::vector<Vertex> from;
    for (long long s : sources) {
        if (s < 0 || std::size_t(s) >= h.mesh.vertices_size())
            throw InvalidArgument("geodesic: source vertex " + std::to_string(s) +
                                  " is out of range (" + std::to_string(h.mesh.vertices_size()) +
                                  " vertices)");
        from.push_back(Vertex(Index(s)));
    }
    GeodesicOptions o;
    o.mass = parse_mass_matrix(mass);
    o.time_factor = time_factor;
    std::vector<double> d;
    {
        py::gil_scoped_release release;
        d = geodesic_distances(h.mesh, from, o);
    }
    return py::array_t<double>(py::ssize_t(d.size()), d.data());
}

/// coloring(name): the value per vertex the viewer's colouring NAME shows (k1, k2, mean,
/// gaussian, shape-index, subdivision, geodesic-distance, ...); NaN where a vertex has none.
py::array_t<double> coloring(const MeshHandle& h, const std::string& name) {
    const VertexColoring c = parse_coloring(name);
    if (c == VertexColoring::None || c == VertexColoring::Normal)
        throw InvalidArgument("coloring: '" + name + "' has no value per vertex");
    VertexColors colors;
    {
        py::gil_scoped_release release;
        colors = color_vertices(h.mesh, c);
    }
    return py::array_t<double>(py::ssize_t(colors.values.size()), colors.values.data());
}

/// inspect(vertex=i | edge=i | face=i): the inspector's fields (trilab-cli inspect --json's
/// element fields): numbers, lists of numbers, or text where the value is words.
py::dict inspect(const MeshHandle& h, std::optional<long long> vertex,
                 std::optional<long long> edge, std::optional<long long> face) {
    const HalfedgeMesh& m = h.mesh;
    if (int(vertex.has_value()) + int(edge.has_value()) + int(face.has_value()) != 1)
        throw InvalidArgument("inspect: give exactly one of vertex=, edge=, face=");
    const auto check = [](long long i, std::size_t size, const char* what) {
        if (i < 0 || std::size_t(i) >= size)
            throw InvalidArgument(std::string("inspect: ") + what + " " + std::to_string(i) +
                                  " is out of range (" + std::to_string(size) + ")");
        return Index(i);
    };
    std::vector<InspectionField> fields;
    if (vertex)
        fields = inspection_fields(
            inspect_vertex(m, Vertex(check(*vertex, m.vertices_size(), "vertex"))));
    else if (edge)
        fields = inspection_fields(inspect_edge(m, Edge(check(*edge, m.edges_size(), "edge"))));
    else
        fields = inspection_fields(inspect_face(m, Face(check(*face, m.faces_size(), "face"))));
    py::dict d;
    for (const InspectionField& f : fields) {
        if (f.numbers.empty())
            d[f.key.c_str()] = f.text;
        else if (f.numbers.size() == 1)
            d[f.key.c_str()] = f.numbers[0];
        else
            d[f.key.c_str()] = f.numbers;
    }
    return d;
}

}  // namespace

void bind_mesh_constructor(py::class_<MeshHandle, std::shared_ptr<MeshHandle>>& cls) {
    cls.def(py::init(&mesh_from_arrays), py::arg("V"), py::arg("F"),
            "A mesh from V, an (n, 3) array of positions (any real dtype, any memory order), and "
            "F, an (m, 3) array of vertex indices (any integer dtype, or reals with whole "
            "values), converted once. Raises ValueError for wrong shapes, non-finite positions, "
            "indices out of range and non-whole float indices. Non-manifold input is repaired "
            "as files are (see load_report).");
}

void bind_mesh_arrays(py::class_<MeshHandle, std::shared_ptr<MeshHandle>>& cls) {
    cls.def_property_readonly(
        "V", [](const py::object& self) { return positions_view(self); },
        "The positions, (n, 3) float64, read-only: a view of the mesh's own memory (no copy).");
    cls.def_property_readonly("F", &face_array, "The faces' vertex indices, (m, 3) int64.");
    cls.def("vertex_property", &vertex_property, py::arg("name"),
            "A vertex property (\"selection\", \"distance\", \"normal\", \"color\", ...) as a new "
            "array, one row per vertex.");
    cls.def("vertex_property_names",
            [](const MeshHandle& h) { return h.mesh.vertex_property_names(); });
    cls.def("spectrum", &spectrum, py::arg("k"), py::arg("operator") = "umbrella",
            py::arg("mass") = "normalizer", py::arg("fix_boundary") = false,
            py::arg("end") = "smallest",
            "The k eigenpairs of K x = lambda S x (core/algorithms/spectral.h): (eigenvalues "
            "(k,), eigenvectors (n, k)), ascending, S-orthonormal.");
    cls.def("laplacian", &laplacian, py::arg("operator") = "curvature-flow",
            py::arg("mass") = "normalizer", py::arg("fix_boundary") = false,
            py::arg("normalized") = false,
            "The operator's symmetric matrix K (normalized=True: L = -S^-1 K) as a "
            "scipy.sparse.csr_matrix (n, n); ImportError without SciPy.");
    cls.def("coloring", &coloring, py::arg("name"),
            "The value per vertex of the viewer's colouring NAME (k1, k2, mean, gaussian, "
            "shape-index, subdivision, geodesic-distance with a \"distance\" property, ...), "
            "(n,) float64, NaN where a vertex has none.");
    cls.def("inspect", &inspect, py::kw_only(), py::arg("vertex") = py::none(),
            py::arg("edge") = py::none(), py::arg("face") = py::none(),
            "What the viewer's inspector shows for one element (as `trilab-cli inspect --json`): "
            "a dict of numbers, lists and words.");
    cls.def("geodesic", &geodesic, py::arg("sources"), py::arg("mass") = "barycentric",
            py::arg("time_factor") = 1.0,
            "Heat-method geodesic distances (n,) from the nearest of the source vertices.");
}

}  // namespace trilab::python
