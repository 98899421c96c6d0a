// libFuzzer target: the session-file and journal readers (app/history/session_file.h). A
// clean trilab::Error is fine; a restored history must hold valid meshes, and a journal's
// prefix must say what it discarded. Anything else aborts.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "app/history/session_file.h"
#include "core/errors.h"
#include "core/validate.h"

namespace {

void check(const trilab::SessionContents& s, std::size_t size) {
    if (s.history.size() == 0 || s.history.size() != s.entries.size()) std::abort();
    if (s.bytes_discarded > size) std::abort();
    for (std::size_t i = 0; i < s.history.size(); ++i)
        for (std::size_t k = 0; k < s.history.info(i).steps.size(); ++k)
            if (!trilab::validate(s.history.mesh(i, k))) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    for (const bool journal : {false, true}) {
        try {
            const trilab::SessionContents s =
                journal ? trilab::read_journal_bytes(bytes, "fuzz.journal", std::size_t(1) << 28)
                        : trilab::read_session_bytes(bytes, "fuzz.trilab", std::size_t(1) << 28);
            check(s, size);
        } catch (const trilab::Error&) {
        }
    }
    return 0;
}
