// Builds an icosphere with the installed trilab::core, checks it and writes it: prints
// "consumer: trilab VERSION, V vertices, F faces, valid".
#include <cstdio>
#include <string>

#include "core/algorithms/generators.h"
#include "core/io/mesh_io.h"
#include "core/validate.h"
#include "trilab/version.h"

int main(int argc, char** argv) {
    const trilab::HalfedgeMesh mesh = trilab::make_icosphere(2);
    const bool valid = trilab::validate(mesh).ok;
    if (argc > 1) trilab::write_mesh(mesh, argv[1]);
    std::printf("consumer: trilab %s, %zu vertices, %zu faces, %s\n", TRILAB_VERSION,
                mesh.n_vertices(), mesh.n_faces(), valid ? "valid" : "INVALID");
    return valid ? 0 : 1;
}
