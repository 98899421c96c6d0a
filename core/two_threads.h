#pragma once
// Splitting a pass over two threads: the large-mesh paths (the builder, validate()) run two
// halves of a pass side by side and join before the next pass.
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>

#include "core/parallel.h"

namespace trilab {

/// Whether a pass over `n` elements is worth a second thread: at least 2^16 elements and
/// thread_count() (core/parallel.h: --threads, TRILAB_THREADS) of at least 2.
inline bool worth_two_threads(std::size_t n) {
    return n >= (std::size_t(1) << 16) && thread_count() >= 2;
}

/// The half of [0, n) that part `part` (0: the lower, 1: the upper) of a two-thread pass
/// takes: [begin, end).
struct HalfRange {
    std::size_t begin, end;
};
inline HalfRange half_of(std::size_t n, int part) {
    return part == 0 ? HalfRange{0, n / 2} : HalfRange{n / 2, n};
}

/// Runs body(0) on a second thread and body(1) here, or body(0) and body(1) here when not
/// `parallel`; rethrows the second thread's exception (after joining it).
template <typename Body>
void on_two_threads(bool parallel, const Body& body) {
    if (!parallel) {
        body(0);
        body(1);
        return;
    }
    std::exception_ptr error;
    std::thread other([&] {
        try {
            body(0);
        } catch (...) {
            error = std::current_exception();
        }
    });
    try {
        body(1);
    } catch (...) {
        other.join();
        throw;
    }
    other.join();
    if (error) std::rethrow_exception(error);
}

/// Runs body(k) for every k in [0, pieces): on two threads when `parallel`, each taking the
/// next piece left (so that neither waits long for the other at the end), else in order here.
/// The pieces are independent; which thread runs a piece is not fixed.
template <typename Body>
void in_pieces(bool parallel, std::size_t pieces, const Body& body) {
    std::atomic<std::size_t> next{0};
    on_two_threads(parallel, [&](int) {
        for (std::size_t k; (k = next.fetch_add(1)) < pieces;) body(k);
    });
}

}  // namespace trilab
