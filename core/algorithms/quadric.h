#pragma once
// Quadric: the error quadric of Garland and Heckbert ("Surface simplification using quadric
// error metrics", SIGGRAPH 1997). A symmetric 4x4 matrix Q = sum w p p^T over planes
// p = (a, b, c, d) (unit normal n = (a, b, c), a x + b y + c z + d = 0), stored as its ten
// distinct coefficients; Q(x) = [x 1] Q [x 1]^T is the weighted sum of squared distances from
// x to the planes. Quadrics add (a merged vertex carries the sum of its parts' planes).
//
// optimize() minimizes Q over space: the 3x3 system A x = -b with A the upper-left block.
// It is solved by Cramer's rule (adjugate / determinant) and refused when the determinant is
// small relative to |A|^3 (a flat or cylindrical neighbourhood, where the minimum is a plane
// or a line and the solution would be arbitrary); the caller then falls back to candidate
// points. A small value type: 80 bytes, no allocation, every operation O(1).
#include <cmath>

#include "core/types.h"

namespace trilab {

class Quadric {
public:
    Quadric() = default;
    /// The quadric of the plane through `point` with unit normal `normal`, times `weight`.
    static Quadric plane(const Vector3& normal, const Point& point, double weight = 1.0) {
        const double a = normal.x(), b = normal.y(), c = normal.z(), d = -normal.dot(point);
        Quadric q;
        q.q_[0] = weight * a * a;
        q.q_[1] = weight * a * b;
        q.q_[2] = weight * a * c;
        q.q_[3] = weight * a * d;
        q.q_[4] = weight * b * b;
        q.q_[5] = weight * b * c;
        q.q_[6] = weight * b * d;
        q.q_[7] = weight * c * c;
        q.q_[8] = weight * c * d;
        q.q_[9] = weight * d * d;
        return q;
    }

    Quadric& operator+=(const Quadric& o) {
        for (int i = 0; i < 10; ++i) q_[i] += o.q_[i];
        return *this;
    }
    friend Quadric operator+(Quadric a, const Quadric& b) { return a += b; }

    /// [x 1] Q [x 1]^T, clamped at 0 (rounding can make it slightly negative).
    double operator()(const Point& x) const {
        const double X = x.x(), Y = x.y(), Z = x.z();
        const double e = q_[0] * X * X + 2 * q_[1] * X * Y + 2 * q_[2] * X * Z + 2 * q_[3] * X +
                         q_[4] * Y * Y + 2 * q_[5] * Y * Z + 2 * q_[6] * Y + q_[7] * Z * Z +
                         2 * q_[8] * Z + q_[9];
        return e > 0 ? e : 0;
    }

    /// The minimizer of Q, written to `x`; false (x untouched) when the 3x3 system is
    /// ill-conditioned: |det A| <= rel_tolerance * |A|_F^3.
    bool optimize(Point& x, double rel_tolerance = 1e-7) const {
        const double a00 = q_[0], a01 = q_[1], a02 = q_[2], a11 = q_[4], a12 = q_[5], a22 = q_[7];
        const double c00 = a11 * a22 - a12 * a12;
        const double c01 = a02 * a12 - a01 * a22;
        const double c02 = a01 * a12 - a02 * a11;
        const double det = a00 * c00 + a01 * c01 + a02 * c02;
        const double norm =
            std::sqrt(a00 * a00 + a11 * a11 + a22 * a22 + 2 * (a01 * a01 + a02 * a02 + a12 * a12));
        if (!(std::abs(det) > rel_tolerance * norm * norm * norm)) return false;
        const double c11 = a00 * a22 - a02 * a02;
        const double c12 = a01 * a02 - a00 * a12;
        const double c22 = a00 * a11 - a01 * a01;
        const double b0 = -q_[3], b1 = -q_[6], b2 = -q_[8];
        const double inv = 1.0 / det;
        x = Point((c00 * b0 + c01 * b1 + c02 * b2) * inv, (c01 * b0 + c11 * b1 + c12 * b2) * inv,
                  (c02 * b0 + c12 * b1 + c22 * b2) * inv);
        return std::isfinite(x.x()) && std::isfinite(x.y()) && std::isfinite(x.z());
    }

    /// The ten coefficients: xx xy xz xw yy yz yw zz zw ww.
    const double* data() const { return q_; }

private:
    double q_[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
};

}  // namespace trilab
