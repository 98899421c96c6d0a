#pragma once
// Small file helpers shared by the readers and writers.
#include <functional>
#include <iosfwd>
#include <string>

#include "core/halfedge_mesh.h"
#include "core/mesh_builder.h"

namespace trilab {

/// The whole file as bytes. Throws IoError if it cannot be opened or read.
std::string read_file_bytes(const std::string& path);

/// Calls `write` on a stream to a temporary file beside `path`, then renames it over
/// `path`. If writing fails (exception or stream error) the temporary file is removed, the
/// target is left untouched, and IoError is thrown.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);

/// Runs build_mesh and turns its InvalidArgument into an IoError naming `path`. A soup
/// without vertices is refused ("the file holds no vertices").
HalfedgeMesh build_mesh_for_file(const PolygonSoup& soup, LoadReport& report,
                                 const std::string& path);

/// Refuses a declared element count that the file cannot possibly hold: `count` elements of
/// at least `min_bytes_each` bytes must fit in `available_bytes`. Prevents huge allocations
/// from a lying header. Throws IoError naming `what`.
void check_declared_count(std::size_t count, std::size_t min_bytes_each,
                          std::size_t available_bytes, const char* what, const std::string& path,
                          std::size_t line);

}  // namespace trilab

namespace trilab {
/// Appends the shortest decimal text that reads back as exactly `value`.
void append_number(std::string& out, double value);
/// Appends a float's shortest round-trip text.
void append_number(std::string& out, float value);
void append_number(std::string& out, std::size_t value);
}  // namespace trilab
