// Placeholder until the operation registry lands.
#include "app/ops/operation.h"

#include "core/errors.h"

namespace trilab {
Operation parse_operation(const std::string& text) {
    throw InvalidArgument("unknown operation '" + text + "'");
}
OperationResult run_operation(const Operation& op, const HalfedgeMesh&, Progress&) {
    throw InvalidArgument("unknown operation '" + op.name + "'");
}
std::vector<std::string> operation_names() { return {}; }
}  // namespace trilab
