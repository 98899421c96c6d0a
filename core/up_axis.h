#pragma once
// Which world axis points up: +y (the OBJ convention, most scanned and game models) or +z
// (CAD, 3D printing, many PLY scans). The viewer's default view and the CLI's --view angles
// keep the up axis up on the screen, and the spherical texture projection puts its poles on
// it (core/algorithms/texcoords.h).
//
// The z-up frame is the y-up frame turned by -90 degrees about x: world (x, y, z) reads as
// (x, z, -y) in y-up terms, so +z is up and -y (the front of a z-up model, where a y-up
// model has +z) faces the default camera.
#include "core/enum_table.h"
#include "core/types.h"

namespace trilab {

enum class UpAxis { Y, Z };
/// The one table of UpAxis (core/enum_table.h): "y" and "z".
inline constexpr EnumEntry<UpAxis> kUpAxes[] = {
    {UpAxis::Y, "y", "+y up"},
    {UpAxis::Z, "z", "+z up"},
};

/// The unit vector of the up axis.
inline Vector3 up_vector(UpAxis up) {
    return up == UpAxis::Z ? Vector3::UnitZ() : Vector3::UnitY();
}
/// The unit vector towards the front of a model (where the default camera sits): +z for y-up,
/// -y for z-up.
inline Vector3 front_vector(UpAxis up) {
    return up == UpAxis::Z ? Vector3(-Vector3::UnitY()) : Vector3::UnitZ();
}
/// "y" or "z".
inline const char* up_axis_name(UpAxis up) {
    return enum_id(EnumTableView<UpAxis>(kUpAxes), up);
}
/// Parses "y" or "z" (also "+y", "+z"); throws InvalidArgument naming `what` otherwise.
inline UpAxis parse_up_axis(std::string name, const char* what = "up axis") {
    if (!name.empty() && name[0] == '+') name.erase(0, 1);
    return parse_enum(EnumTableView<UpAxis>(kUpAxes), name, what);
}

}  // namespace trilab
