#include "tests/support/skip.h"

#include <catch2/catch.hpp>

#include <atomic>
#include <filesystem>

namespace trilab::test {

namespace {
std::atomic<int> g_skips{0};
}  // namespace

void skip(const std::string& reason) {
    ++g_skips;
    WARN("skipped: " << reason);
}

int skips_recorded() {
    return g_skips.load();
}

bool present_or_skip(const std::string& path) {
    if (std::filesystem::exists(path)) return true;
    skip(path + " is absent (../shared not beside the repository?)");
    return false;
}

}  // namespace trilab::test
