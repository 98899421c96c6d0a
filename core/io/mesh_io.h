#pragma once
// Reading and writing mesh files. The format is chosen by the file extension:
//   .obj  Wavefront OBJ (positions, texture coordinates, normals; polygons triangulated)
//   .off  Object File Format (OFF, COFF, NOFF, STOFF and combinations; polygons)
//   .ply  Stanford PLY, ASCII and binary little/big endian (faces and tristrips)
//   .stl  STL, ASCII or binary (decided by the binary size rule 84 + 50 n)
//   .om   OpenMesh binary, read 1.2 to 2.2, written as 2.2
// Readers throw IoError naming the file, the line (text formats) and the reason; nothing is
// returned half-loaded. Only regular files are read, up to a size limit derived from the
// available memory (core/io/file_util.h: read_file_bytes). Text formats skip a UTF-8
// byte-order mark and refuse UTF-16 and UTF-32. NaN and infinity are refused in every
// attribute (positions, normals, colours, texture coordinates): text formats name the line,
// binary formats the element. Writers never write what their reader refuses: a non-finite
// value is refused; values that float32 cannot hold are written as double where the format
// has double (PLY), else refused naming the format (binary STL positions, .om texture
// coordinates); STL refuses a mesh without faces. Writers go through write_file_atomically
// (a temporary file in the target's folder, renamed over it; see file_util.h for symbolic
// links, hard links, permissions and what is never replaced), so a failed write leaves any
// existing file untouched.
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "core/halfedge_mesh.h"
#include "core/mesh_builder.h"

namespace trilab {

struct LoadedMesh {
    HalfedgeMesh mesh;
    LoadReport report;
    /// A texture image the file refers to (OBJ: map_Kd of its material library), or "".
    std::string texture_path;
};

struct WriteOptions {
    bool ascii = false;           ///< PLY and STL: write text instead of binary
    bool big_endian = false;      ///< binary PLY: big-endian instead of little-endian
    bool write_normals = true;    ///< write "v:normal" where the format can carry it
    bool write_colors = true;     ///< write "v:color" where the format can carry it
    bool write_texcoords = true;  ///< write "v:texcoord" / "h:texcoord" where possible
};

/// What a mesh format is and what its writer can carry (the table in mesh_io.cpp, which also
/// dispatches reading and writing).
struct MeshFormatInfo {
    const char* extension;   ///< lower case, without the dot
    const char* name;        ///< e.g. "Stanford PLY"
    bool normals;            ///< writes "v:normal" (WriteOptions::write_normals)
    bool colors;             ///< writes "v:color" (WriteOptions::write_colors)
    bool texcoords;          ///< writes texture coordinates (WriteOptions::write_texcoords)
    bool ascii_choice;       ///< WriteOptions::ascii applies (binary otherwise)
    bool big_endian_choice;  ///< WriteOptions::big_endian applies
    bool features;           ///< writes "e:sharpness" and "v:corner" (core/features.h)
};
/// Every supported format, in the order of supported_mesh_extensions().
const std::vector<MeshFormatInfo>& mesh_formats();
/// Formats by lower-case extension without the dot: "obj", "off", "ply", "stl", "om".
std::vector<std::string> supported_mesh_extensions();
/// The lower-case extension of `path` without the dot ("" when there is none).
std::string file_extension(const std::string& path);

/// Reads any supported format (chosen by extension). A closed mesh with a negative volume
/// gets a note in its report (core/algorithms/orientation.h inward_orientation_note()).
LoadedMesh read_mesh(const std::string& path);
/// The same, calling `on_soup` (core/io/file_util.h: SoupObserver) with the file's polygon
/// soup once the whole file is read and checked (indices in range, values finite), before
/// the half-edge mesh is built: a caller may show something of a large file early. Called at
/// most once, on this thread; not for an .om file that holds its half-edge connectivity.
LoadedMesh read_mesh(const std::string& path,
                     const std::function<void(const PolygonSoup&)>& on_soup);
/// The save report: what writing `mesh` to `path` leaves out that the mesh holds (features in a
/// format without edges); empty when nothing is lost or the extension is unknown.
std::vector<std::string> write_notes(const HalfedgeMesh& mesh, const std::string& path);
/// Writes any supported format (chosen by extension).
void write_mesh(const HalfedgeMesh& mesh, const std::string& path,
                const WriteOptions& options = {});

// Per-format entry points (same contracts as above).
LoadedMesh read_obj(const std::string& path);
void write_obj(const HalfedgeMesh& mesh, const std::string& path, const WriteOptions& options);
LoadedMesh read_off(const std::string& path);
void write_off(const HalfedgeMesh& mesh, const std::string& path, const WriteOptions& options);
LoadedMesh read_ply(const std::string& path);
void write_ply(const HalfedgeMesh& mesh, const std::string& path, const WriteOptions& options);
LoadedMesh read_stl(const std::string& path);
void write_stl(const HalfedgeMesh& mesh, const std::string& path, const WriteOptions& options);
LoadedMesh read_om(const std::string& path);
void write_om(const HalfedgeMesh& mesh, const std::string& path, const WriteOptions& options);

// Writing to a stream: what the path writers write, for tests and fuzzers. `name` labels
// the errors and chooses the format by its extension (write_mesh_to); the same checks and
// refusals as the path writers.
void write_mesh_to(const HalfedgeMesh& mesh, std::ostream& out, const std::string& name,
                   const WriteOptions& options = {});
/// write_mesh_to into a string.
std::string write_mesh_bytes(const HalfedgeMesh& mesh, const std::string& name,
                             const WriteOptions& options = {});
void write_obj_to(const HalfedgeMesh& mesh, std::ostream& out, const std::string& name,
                  const WriteOptions& options);
void write_off_to(const HalfedgeMesh& mesh, std::ostream& out, const std::string& name,
                  const WriteOptions& options);
void write_ply_to(const HalfedgeMesh& mesh, std::ostream& out, const std::string& name,
                  const WriteOptions& options);
void write_stl_to(const HalfedgeMesh& mesh, std::ostream& out, const std::string& name,
                  const WriteOptions& options);
void write_om_to(const HalfedgeMesh& mesh, std::ostream& out, const std::string& name,
                 const WriteOptions& options);

// In-memory readers: parse a whole file's `bytes` already in memory (the path readers read
// the file and call these; the fuzzers call them directly). `name` only labels the errors
// and the report. The OBJ variant does not look for material libraries (it has no folder).
LoadedMesh read_obj_bytes(const std::string& bytes, const std::string& name);
LoadedMesh read_off_bytes(const std::string& bytes, const std::string& name);
LoadedMesh read_ply_bytes(const std::string& bytes, const std::string& name);
LoadedMesh read_stl_bytes(const std::string& bytes, const std::string& name);
LoadedMesh read_om_bytes(const std::string& bytes, const std::string& name);

}  // namespace trilab
