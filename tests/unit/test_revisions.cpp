// Mesh revisions (HalfedgeMesh::revision(), core/property.h): every write access changes the
// revision of what it may have changed, and only that; copies share revisions while they share
// values; reading never changes one; equal revisions mean equal contents.
#include <thread>
#include <utility>
#include <vector>

#include "core/algorithms/generators.h"
#include "core/algorithms/subdivision.h"
#include "core/algorithms/texcoords.h"
#include "core/progress.h"
#include "test_helpers.h"

using namespace trilab;

TEST_CASE("a write changes the revision of what it may have changed, and only that",
          "[core][revision]") {
    HalfedgeMesh a = make_icosphere(2);
    const HalfedgeMesh::Revision r0 = a.revision();
    CHECK(r0.topology != 0);
    CHECK(r0.geometry != 0);
    CHECK(r0.attributes != 0);
    CHECK(a.revision() == r0);  // asking again draws nothing new

    // Reading through a const mesh changes nothing.
    const HalfedgeMesh& ca = a;
    double sum = 0;
    for (Vertex v : ca.vertices()) sum += ca.position(v).x() + double(ca.valence(v));
    (void)sum;
    CHECK(a.revision() == r0);

    // Positions: geometry only.
    a.position(Vertex(0)) += Point(0.1, 0, 0);
    const HalfedgeMesh::Revision r1 = a.revision();
    CHECK(r1.geometry != r0.geometry);
    CHECK(r1.topology == r0.topology);
    CHECK(r1.attributes == r0.attributes);
    std::vector<Point> moved = a.positions();
    a.set_positions(std::move(moved));
    CHECK(a.geometry_revision() != r1.geometry);
    CHECK(a.topology_revision() == r0.topology);

    // An edge flip: topology only.
    const HalfedgeMesh::Revision r2 = a.revision();
    const Edge flippable = test::first_flippable_edge(a);
    REQUIRE(flippable.is_valid());
    a.flip(flippable);
    REQUIRE_VALID(a);
    const HalfedgeMesh::Revision r3 = a.revision();
    CHECK(r3.topology != r2.topology);
    CHECK(r3.geometry == r2.geometry);
    CHECK(r3.attributes == r2.attributes);

    // Attributes: adding, writing and removing one each change the attribute revision only.
    auto uv = a.add_vertex_property<TexCoord>("v:texcoord");
    const std::uint64_t added = a.attribute_revision();
    CHECK(added != r3.attributes);
    uv[Vertex(1)] = TexCoord(0.5, 0.5);
    const std::uint64_t written = a.attribute_revision();
    CHECK(written != added);
    a.remove_vertex_property("v:texcoord");
    CHECK(a.attribute_revision() != written);
    CHECK(a.topology_revision() == r3.topology);
    CHECK(a.geometry_revision() == r3.geometry);
}

TEST_CASE("copies share revisions while they share values, separate meshes never do",
          "[core][revision]") {
    HalfedgeMesh a = make_icosphere(2);
    const HalfedgeMesh::Revision ra = a.revision();
    HalfedgeMesh b = a;
    CHECK(b.revision() == ra);
    HalfedgeMesh moved = std::move(b);
    CHECK(moved.revision() == ra);

    // The copy moves: its geometry revision changes, the original's does not.
    moved.position(Vertex(3)) *= 1.01;
    CHECK(moved.geometry_revision() != ra.geometry);
    CHECK(a.revision() == ra);

    // Two meshes built the same way have the same contents but their own revisions.
    const HalfedgeMesh twin = make_icosphere(2);
    CHECK(twin.topology_revision() != ra.topology);
    CHECK(twin.geometry_revision() != ra.geometry);

    // A copy that removes an attribute the original keeps differs from it, even though every
    // remaining array is shared (the set of arrays is part of the attribute revision).
    HalfedgeMesh with = a;
    with.add_vertex_property<float>("v:weight", 1.0f);
    HalfedgeMesh without = with;
    CHECK(without.revision() == with.revision());
    without.remove_vertex_property("v:weight");
    CHECK(without.attribute_revision() != with.attribute_revision());
}

TEST_CASE("operations produce meshes with new revisions where they changed something",
          "[core][revision]") {
    const HalfedgeMesh base = make_icosphere(1);
    const HalfedgeMesh::Revision r = base.revision();
    SubdivisionOptions o;
    o.scheme = SubdivisionScheme::Loop;
    NullProgress progress;
    const HalfedgeMesh fine = subdivide(base, o, progress).levels.back().mesh;
    CHECK(fine.topology_revision() != r.topology);
    CHECK(fine.geometry_revision() != r.geometry);

    HalfedgeMesh projected = base;
    project_texcoords(projected, TexCoordProjection::Spherical, UpAxis::Y);
    CHECK(projected.attribute_revision() != r.attributes);
    CHECK(projected.topology_revision() == r.topology);
    CHECK(projected.geometry_revision() == r.geometry);
    CHECK(base.revision() == r);
}

TEST_CASE("threads asking a const mesh for its revision at once agree on one", "[core][revision]") {
    HalfedgeMesh a = make_icosphere(2);
    a.position(Vertex(0)) *= 1.5;  // no revision drawn since this write
    const HalfedgeMesh& ca = a;
    std::vector<HalfedgeMesh::Revision> seen(4);
    std::vector<std::thread> threads;
    for (std::size_t i = 0; i < seen.size(); ++i)
        threads.emplace_back([&ca, &seen, i] { seen[i] = ca.revision(); });
    for (std::thread& t : threads) t.join();
    for (const HalfedgeMesh::Revision& r : seen) CHECK(r == seen[0]);
    CHECK(ca.revision() == seen[0]);
}
