#pragma once
// SessionFrequency: the frequency document (the Frequency panel): the decomposition job,
// the live band (positions only, shown as a Band), the history entries made when a slider is
// released or Restore is pressed, and whether the decomposition still fits the current state.
// The decomposition itself lives in the document (Document::frequency), which every owner
// reads.
#include <cstddef>

#include "app/session/session_core.h"
#include "app/session/session_morph.h"
#include "core/algorithms/spectral.h"

namespace trilab::viewer {

class SessionFrequency {
public:
    SessionFrequency(SessionCore& core, SessionMorph& morph) : core_(core), morph_(morph) {}

    /// Decomposes the current state as a job (SessionEvents::decomposed_hi when it ends).
    void decompose(const SpectralOptions& options);
    /// Shows the band [lo, hi] live (positions only, no history entry).
    void preview_band(std::size_t lo, std::size_t hi);
    /// Pushes the band (or, with `restore`, the decomposed shape) as a history entry.
    void push_band(std::size_t lo, std::size_t hi, bool restore);
    /// The decomposition's validity and applied band for the current state (it changes only
    /// with the state or the decomposition: called there, not every frame).
    void follow_document();

private:
    SessionCore& core_;
    SessionMorph& morph_;
};

}  // namespace trilab::viewer
