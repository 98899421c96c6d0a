#pragma once
// DenoiseTool: the Denoise section's tool (the "denoise" operation, app/ops/denoise_op.cpp).
// Its panel is the operation's live-preview panel, and, when the session has a frequency
// decomposition of the current mesh, what the preview shown does to each frequency band: the
// energy of the document's positions and of the preview's in each band, drawn side by side
// (a denoiser should take out the high bands' noise and keep the high bands that carry the
// edges, where smoothing takes them all). Computed while the section is open, when the preview
// result changes (O(k · rows) on a worker thread, from copies), and cached.
// The worked example of docs/recipes.md "A new operation with a panel of its own".
#include <cstddef>
#include <future>
#include <string>
#include <vector>

#include "app/viewer/operation_tool.h"
#include "core/algorithms/spectral.h"

namespace trilab::viewer {

/// The energy of two sets of positions in bands of a decomposition: band b holds the
/// computed frequencies [lo[b], hi[b]]; when `rest` is set the last band is everything the
/// computed frequencies do not carry (the uncomputed frequencies). The energy of positions X
/// in a band is the S-norm of their projection on its eigenvectors, sum |α_k|² with
/// α = Eᵀ·S·X over the band's k; the rest's is ||X||²_S less every computed one.
struct BandEnergies {
    std::vector<std::size_t> lo, hi;
    bool rest = false;
    std::vector<double> before, after;
    std::size_t size() const { return before.size(); }
};

/// The energies of `before` and `after` (one position per vertex storage index, as
/// mesh.positions()) in `bands` bands of equal count over the computed frequencies (fewer
/// when there are fewer frequencies), plus the rest when the decomposition is partial.
/// Throws InvalidArgument when a size differs from the decomposed mesh's vertices or
/// `bands` is 0. O(k · rows).
BandEnergies band_energies(const SpectralDecomposition& d, const std::vector<Point>& before,
                           const std::vector<Point>& after, std::size_t bands);

class DenoiseTool : public OperationTool {
public:
    explicit DenoiseTool(ViewerContext& context);
    void update() override;
    void section(const SidebarContext& context, CommandQueue& commands) override;
    PanelEntries panels() override;
    void settings(SettingsVisitor& v) override;
    bool show_figure(const Operation& op) override { return take_figure(panel_, op); }
    OperationPanelState& panel() { return panel_; }
    /// The band energies of the preview shown against the document (empty: no preview of
    /// this panel, or no decomposition of the current mesh).
    const BandEnergies& bands() const { return bands_; }
    /// How many times the energies were computed (the cache's test).
    std::size_t computations() const { return computations_; }
    /// Waits for the energies being computed on the worker thread and takes them (tests).
    void finish();

    static constexpr std::size_t kBands = 8;

private:
    void update_bands();
    OperationPanelState panel_{"denoise"};
    BandEnergies bands_;
    std::string bands_key_;  ///< what bands_ was (is being) computed for
    std::size_t computations_ = 0;
    std::future<BandEnergies> bands_job_;  ///< O(k · rows), off the render thread
};

}  // namespace trilab::viewer
