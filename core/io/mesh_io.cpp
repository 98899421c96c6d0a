#include "core/io/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <sstream>

#include "core/algorithms/orientation.h"
#include "core/errors.h"
#include "core/features.h"
#include "core/io/file_util.h"

namespace trilab {

namespace {

/// A format: what it is and carries, and its reader and writers.
struct MeshFormat {
    MeshFormatInfo info;
    LoadedMesh (*read)(const std::string& path);
    void (*write)(const HalfedgeMesh& mesh, const std::string& path, const WriteOptions& options);
    void (*write_to)(const HalfedgeMesh& mesh, std::ostream& out, const std::string& name,
                     const WriteOptions& options);
};

/// The one table of mesh formats: read and write dispatch, the lists and the messages.
/// info: extension, name, normals, colors, texcoords, ascii choice, big-endian choice.
const MeshFormat kMeshFormats[] = {
    {{"obj", "Wavefront OBJ", true, false, true, false, false, false},
     read_obj,
     write_obj,
     write_obj_to},
    {{"off", "OFF", true, true, true, false, false, false}, read_off, write_off, write_off_to},
    {{"ply", "Stanford PLY", true, true, true, true, true, true},
     read_ply,
     write_ply,
     write_ply_to},
    {{"stl", "STL", false, false, false, true, false, false}, read_stl, write_stl, write_stl_to},
    {{"om", "OpenMesh binary", true, true, true, false, false, true},
     read_om,
     write_om,
     write_om_to},
};

/// The format of `path`'s extension, or null.
const MeshFormat* format_of(const std::string& path) {
    const std::string ext = file_extension(path);
    for (const MeshFormat& f : kMeshFormats)
        if (ext == f.info.extension) return &f;
    return nullptr;
}

[[noreturn]] void unknown_format(const std::string& path) {
    std::string supported;
    for (const MeshFormat& f : kMeshFormats)
        supported += (supported.empty() ? "." : ", .") + std::string(f.info.extension);
    throw IoError(
        path, 0,
        "unknown mesh format '." + file_extension(path) + "' (supported: " + supported + ")");
}

}  // namespace

const std::vector<MeshFormatInfo>& mesh_formats() {
    static const std::vector<MeshFormatInfo> formats = [] {
        std::vector<MeshFormatInfo> out;
        for (const MeshFormat& f : kMeshFormats) out.push_back(f.info);
        return out;
    }();
    return formats;
}

std::vector<std::string> write_notes(const HalfedgeMesh& mesh, const std::string& path) {
    const MeshFormat* f = format_of(path);
    std::vector<std::string> notes;
    if (!f) return notes;
    const std::string features = feature_save_note(mesh, f->info.features);
    if (!features.empty()) notes.push_back(features);
    return notes;
}

std::vector<std::string> supported_mesh_extensions() {
    std::vector<std::string> out;
    for (const MeshFormat& f : kMeshFormats) out.push_back(f.info.extension);
    return out;
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

LoadedMesh read_mesh(const std::string& path) {
    const MeshFormat* format = format_of(path);
    if (!format) {
        // "/dev/zero: not a regular file: it is a character device" says more than its
        // extension.
        std::error_code ec;
        if (std::filesystem::exists(path, ec)) check_regular_file(path);
        unknown_format(path);
    }
    LoadedMesh loaded = format->read(path);
    std::string note = inward_orientation_note(loaded.mesh);
    if (!note.empty()) loaded.report.notes.push_back(std::move(note));
    return loaded;
}

LoadedMesh read_mesh(const std::string& path,
                     const std::function<void(const PolygonSoup&)>& on_soup) {
    const ScopedSoupObserver observing(&on_soup);
    return read_mesh(path);
}

void write_mesh(const HalfedgeMesh& mesh, const std::string& path, const WriteOptions& options) {
    const MeshFormat* format = format_of(path);
    if (!format) unknown_format(path);
    format->write(mesh, path, options);
}

void write_mesh_to(const HalfedgeMesh& mesh, std::ostream& out, const std::string& name,
                   const WriteOptions& options) {
    const MeshFormat* format = format_of(name);
    if (!format) unknown_format(name);
    format->write_to(mesh, out, name, options);
}

std::string write_mesh_bytes(const HalfedgeMesh& mesh, const std::string& name,
                             const WriteOptions& options) {
    std::ostringstream out(std::ios::binary);
    write_mesh_to(mesh, out, name, options);
    return out.str();
}

}  // namespace trilab
