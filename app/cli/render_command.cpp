#include "app/cli/render_command.h"

#include "core/errors.h"

namespace trilab::cli {

int run_render_command(const std::vector<std::string>&) {
    throw Error("render: not implemented yet");
}

}  // namespace trilab::cli
