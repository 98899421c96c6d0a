// Every reader either loads a valid mesh or throws IoError on damaged input: random byte
// changes, insertions, truncations and pure garbage, for every format and encoding. The seed
// is fixed so failures reproduce; TRILAB_FUZZ_ROUNDS raises the number of rounds.
#include <cstdlib>
#include <fstream>
#include <random>

#include "core/algorithms/generators.h"
#include "core/errors.h"
#include "core/io/file_util.h"
#include "core/io/mesh_io.h"
#include "test_helpers.h"

using namespace trilab;
using namespace trilab::test;

namespace {
void write_bytes(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

/// Reads `path`; returns true when it loaded (and then it must be valid).
bool load_or_refuse(const std::string& path) {
    try {
        LoadedMesh l = read_mesh(path);
        REQUIRE_VALID(l.mesh);
        return true;
    } catch (const IoError& e) {
        REQUIRE(std::string(e.what()).find(path) != std::string::npos);
        return false;
    }
}
}  // namespace

TEST_CASE("damaged files of every format load valid or throw IoError", "[io][robustness]") {
    // Damaged bytes decode to any value, NaN and infinity included: the readers must find
    // them, so they run without floating-point traps.
    const FpTrapsOff traps_off;
    int rounds = 150;
    if (const char* env = std::getenv("TRILAB_FUZZ_ROUNDS")) rounds = std::max(1, std::atoi(env));
    TempDir dir;
    HalfedgeMesh source = attributed_sphere();
    struct Variant {
        const char* name;
        bool ascii, big_endian;
    };
    const Variant variants[] = {{"a.obj", false, false}, {"a.off", false, false},
                                {"a.ply", false, false}, {"b.ply", true, false},
                                {"c.ply", false, true},  {"a.stl", false, false},
                                {"b.stl", true, false},  {"a.om", false, false}};
    std::mt19937 rng(20261122);
    for (const Variant& v : variants) {
        WriteOptions o;
        o.ascii = v.ascii;
        o.big_endian = v.big_endian;
        write_mesh(source, dir.path(v.name), o);
        const std::string original = read_file_bytes(dir.path(v.name));
        const std::string damaged_path = dir.path(std::string("damaged_") + v.name);
        int loaded = 0, refused = 0;
        for (int round = 0; round < rounds; ++round) {
            std::string bytes = original;
            const int kind = int(rng() % 4);
            if (kind == 0) {  // change a few bytes
                for (int k = 0, n = 1 + int(rng() % 8); k < n; ++k)
                    bytes[rng() % bytes.size()] = char(rng());
            } else if (kind == 1) {  // truncate
                bytes.resize(rng() % bytes.size());
            } else if (kind == 2) {  // insert bytes
                bytes.insert(rng() % bytes.size(), std::string(1 + rng() % 16, char(rng())));
            } else {  // garbage with the format's first bytes
                std::string garbage(bytes.substr(0, std::min<std::size_t>(bytes.size(), 16)));
                for (int k = 0, n = int(rng() % 4096); k < n; ++k) garbage += char(rng());
                bytes = garbage;
            }
            write_bytes(damaged_path, bytes);
            INFO(v.name << " round " << round << " kind " << kind);
            (load_or_refuse(damaged_path) ? loaded : refused)++;
        }
        INFO(v.name);
        REQUIRE(loaded + refused == rounds);
    }
}
