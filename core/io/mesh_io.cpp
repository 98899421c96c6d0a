#include "core/io/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <sstream>

#include "core/algorithms/orientation.h"
#include "core/errors.h"
#include "core/io/file_util.h"

namespace trilab {

std::vector<std::string> supported_mesh_extensions() {
    return {"obj", "off", "ply", "stl", "om"};
}

std::string file_extension(const std::string& path) {
    const std::size_t slash = path.find_last_of("/\\");
    const std::size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

namespace {
[[noreturn]] void unknown_format(const std::string& path) {
    throw IoError(path, 0,
                  "unknown mesh format '." + file_extension(path) +
                      "' (supported: .obj, .off, .ply, .stl, .om)");
}
}  // namespace

namespace {
LoadedMesh read_by_extension(const std::string& path) {
    const std::string ext = file_extension(path);
    if (ext == "obj") return read_obj(path);
    if (ext == "off") return read_off(path);
    if (ext == "ply") return read_ply(path);
    if (ext == "stl") return read_stl(path);
    if (ext == "om") return read_om(path);
    // "/dev/zero: not a regular file: it is a character device" says more than its extension.
    std::error_code ec;
    if (std::filesystem::exists(path, ec)) check_regular_file(path);
    unknown_format(path);
}
}  // namespace

LoadedMesh read_mesh(const std::string& path) {
    LoadedMesh loaded = read_by_extension(path);
    std::string note = inward_orientation_note(loaded.mesh);
    if (!note.empty()) loaded.report.notes.push_back(std::move(note));
    return loaded;
}

void write_mesh(const HalfedgeMesh& mesh, const std::string& path, const WriteOptions& options) {
    const std::string ext = file_extension(path);
    if (ext == "obj") return write_obj(mesh, path, options);
    if (ext == "off") return write_off(mesh, path, options);
    if (ext == "ply") return write_ply(mesh, path, options);
    if (ext == "stl") return write_stl(mesh, path, options);
    if (ext == "om") return write_om(mesh, path, options);
    unknown_format(path);
}

void write_mesh_to(const HalfedgeMesh& mesh, std::ostream& out, const std::string& name,
                   const WriteOptions& options) {
    const std::string ext = file_extension(name);
    if (ext == "obj") return write_obj_to(mesh, out, name, options);
    if (ext == "off") return write_off_to(mesh, out, name, options);
    if (ext == "ply") return write_ply_to(mesh, out, name, options);
    if (ext == "stl") return write_stl_to(mesh, out, name, options);
    if (ext == "om") return write_om_to(mesh, out, name, options);
    unknown_format(name);
}

std::string write_mesh_bytes(const HalfedgeMesh& mesh, const std::string& name,
                             const WriteOptions& options) {
    std::ostringstream out(std::ios::binary);
    write_mesh_to(mesh, out, name, options);
    return out.str();
}

}  // namespace trilab
