#pragma once
// validate(): checks every connectivity invariant of a HalfedgeMesh (listed in
// halfedge_mesh.h) and the feature properties (core/features.h: check_features()), and
// reports the first violation. Tests call it after every operation.
// Complexity: linear in the mesh size.
#include <string>

#include "core/halfedge_mesh.h"

namespace trilab {

struct ValidationResult {
    bool ok = true;
    std::string message;  ///< the first violation found, empty when ok
    explicit operator bool() const { return ok; }
};

ValidationResult validate(const HalfedgeMesh& mesh);

}  // namespace trilab
