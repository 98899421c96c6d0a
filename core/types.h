#pragma once
// Scalar and vector types shared by the whole core.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace trilab {

using Scalar = double;
using Point = Eigen::Vector3d;     ///< a position in space
using Vector3 = Eigen::Vector3d;   ///< a direction or normal
using TexCoord = Eigen::Vector2d;  ///< (u, v) texture coordinates
using Color = Eigen::Vector3f;     ///< linear RGB in [0, 1]

}  // namespace trilab
