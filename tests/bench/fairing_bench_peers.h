#pragma once
// The fairing benchmark's peers (tests/bench/fairing_bench_peers.cpp): OpenMesh's
// JacobiLaplaceSmootherT and CGAL's smooth_shape, each compiled in only when found.
#include "core/halfedge_mesh.h"

/// Times the peers and trilab's matching runs on the same meshes and prints the ratios.
/// `bunny` may be null (the shared mesh is absent): the CGAL row is skipped then.
void run_peers(const trilab::HalfedgeMesh* bunny, const trilab::HalfedgeMesh& large, int runs);
