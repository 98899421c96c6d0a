#pragma once
// Running a pass on every core: a fixed pool of worker threads and loops over FIXED blocks.
//
// parallel_for(begin, end, fn) cuts [begin, end) into blocks of a fixed size (kBlock elements,
// or the size the caller names), independent of the number of threads, and hands them out to
// the pool's threads and the calling one; parallel_reduce() computes one partial per block and
// combines the partials in block order on the calling thread. So a pass that writes each output
// from its own element, or reduces through parallel_reduce(), gives the same bits for any
// number of threads (1, 2, 7 or every core): only which thread runs a block changes.
//
// The number of threads (thread_count()) is global: every core by default, the environment
// variable TRILAB_THREADS where set (read on first use, so the viewer and the Python module
// follow it too), or set_thread_count() (trilab-cli --threads N). A loop started from inside a
// block (nested), or while another thread's loop holds the pool, runs its blocks in order on
// its own thread: the same blocks, the same bits.
//
// The first exception a block throws stops the handing out of blocks and is rethrown on the
// calling thread once every thread has left the loop; outputs of the blocks that ran stay
// written (callers write into scratch arrays or a mesh they discard on failure).
// Overhead: one wake-up of the pool per loop (some microseconds), one indirect call per block.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace trilab {

/// The default block: 2^12 elements (big enough that a block's work hides its hand-out, small
/// enough that two threads share a 10^5-element pass evenly).
constexpr std::size_t kBlock = std::size_t(1) << 12;

/// The machine's hardware threads (std::thread::hardware_concurrency(), at least 1).
int hardware_threads();

/// The threads a parallel loop uses (at least 1): set_thread_count()'s, else TRILAB_THREADS's,
/// else hardware_threads().
int thread_count();

/// Sets thread_count(): n in [1, kMaxThreads], or 0 for every core (hardware_threads()).
/// Throws InvalidArgument for another n (nothing changes).
void set_thread_count(int n);
constexpr int kMaxThreads = 1024;

/// Parses a thread count as --threads and TRILAB_THREADS take it: a whole number in
/// [1, kMaxThreads], or 0 for every core. Throws InvalidArgument naming `what` and the text.
int parse_thread_count(const std::string& text, const std::string& what);

/// Applies TRILAB_THREADS now when it is set (else nothing): throws InvalidArgument naming the
/// variable when its value does not parse (trilab-cli checks it at start; the lazy read in
/// thread_count() ignores a value that does not parse and uses every core).
void apply_thread_environment();

/// The number of blocks of `block` elements that cover [begin, end).
inline std::size_t block_count(std::size_t begin, std::size_t end, std::size_t block = kBlock) {
    return end > begin ? (end - begin + block - 1) / block : 0;
}

namespace detail {
/// Runs body(k) for every block k in [0, blocks) on up to thread_count() threads (the caller's
/// included); rethrows the first exception. The heart of every loop below.
void run_blocks(std::size_t blocks, const std::function<void(std::size_t)>& body);
/// Whether this thread is running a block of a parallel loop (a loop started here runs in order).
bool in_block();
}  // namespace detail

/// Runs fn(b, e) for every block [b, e) of `block` elements of [begin, end), blocks possibly at
/// the same time on several threads.
template <typename Fn>
void parallel_for_blocks(std::size_t begin, std::size_t end, const Fn& fn,
                         std::size_t block = kBlock) {
    const std::size_t blocks = block_count(begin, end, block);
    if (blocks == 0) return;
    if (blocks == 1) {
        fn(begin, end);
        return;
    }
    detail::run_blocks(blocks, [&](std::size_t k) {
        const std::size_t b = begin + k * block;
        fn(b, b + block < end ? b + block : end);
    });
}

/// Runs fn(i) for every i in [begin, end), in blocks of `block` elements.
template <typename Fn>
void parallel_for(std::size_t begin, std::size_t end, const Fn& fn, std::size_t block = kBlock) {
    parallel_for_blocks(
        begin, end,
        [&](std::size_t b, std::size_t e) {
            for (std::size_t i = b; i < e; ++i) fn(i);
        },
        block);
}

/// Runs fn(b, e) on thread_count() contiguous ranges [b, e) of [begin, end) (one per thread; one
/// range below `min_size` elements). Unlike the loops above, the partition follows the thread
/// count: for passes where a thread owns the outputs of its range and every output's value
/// does not depend on the partition (an owner scan: each thread reads all the input and
/// accumulates only into its own range's outputs, in input order, which keeps each output's
/// sum in the input's order: the bits of a one-thread scatter).
template <typename Fn>
void parallel_ranges(std::size_t begin, std::size_t end, const Fn& fn,
                     std::size_t min_size = kBlock) {
    const std::size_t n = end > begin ? end - begin : 0;
    std::size_t parts = std::size_t(thread_count());
    if (n < 2 * min_size || parts < 2 || detail::in_block()) parts = 1;
    if (parts == 1) {
        if (n > 0) fn(begin, end);
        return;
    }
    detail::run_blocks(
        parts, [&](std::size_t k) { fn(begin + n * k / parts, begin + n * (k + 1) / parts); });
}

/// Deterministic reduction: partial(b, e) -> T for every block [b, e), then
/// combine(combine(combine(init, p_0), p_1), ...) in block order on the calling thread. The
/// result depends on `block`, never on the number of threads.
template <typename T, typename Partial, typename Combine>
T parallel_reduce(std::size_t begin, std::size_t end, T init, const Partial& partial,
                  const Combine& combine, std::size_t block = kBlock) {
    const std::size_t blocks = block_count(begin, end, block);
    // One slot per block, each its own object: a std::vector<bool> would pack the partials of
    // several blocks into one word, which threads would write at the same time (a data race
    // ThreadSanitizer found in denoise's all-finite flag).
    struct Slot {
        T value;
    };
    std::vector<Slot> parts(blocks, Slot{init});
    parallel_for_blocks(
        begin, end,
        [&](std::size_t b, std::size_t e) { parts[(b - begin) / block].value = partial(b, e); },
        block);
    T result = init;
    for (const Slot& p : parts) result = combine(result, p.value);
    return result;
}

}  // namespace trilab
