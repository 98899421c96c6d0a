#include "app/viewer/frequency_tool.h"

#include <algorithm>
#include <vector>

#include "app/ops/operation_entries.h"
#include "app/ops/spectrum_op.h"
#include "core/algorithms/coloring.h"
#include "core/algorithms/transfer_function.h"

namespace trilab::viewer {

void FrequencyTool::update() {
    const auto& d = context_.session.document().frequency.decomposition;
    if (d.get() == decomposition_) return;
    decomposition_ = d.get();
    if (d && !d->empty()) on_decomposed(d->size() - 1);
}

void FrequencyTool::on_decomposed(std::size_t hi) {
    // A new decomposition: the band's sliders cover it, the first frequency is visualised.
    FrequencyPanelState& s = panel_;
    s.lo = 0;
    s.hi = int(hi);
    s.visualize = std::min(1, s.hi);
    if (coloring_needs_field(context_.view.settings.coloring))
        context_.commands.push_back(UpdateColoring{});
}

void FrequencyTool::section(const SidebarContext& context, CommandQueue& commands) {
    const FrequencyDocument no_decomposition;
    frequency_window(panel_, context.frequency ? *context.frequency : no_decomposition,
                     context.busy, commands);
}

PanelEntries FrequencyTool::panels() {
    PanelEntry entry;
    entry.name = "frequency";
    entry.title = "Frequency decomposition";
    entry.open = &panel_.open;
    entry.menu = PanelMenu::Algorithms;
    return {entry};
}

void FrequencyTool::settings(SettingsVisitor& v) {
    v.operation("panel.frequency", panel_.op);
    v.number("frequency.lo", panel_.lo);
    v.number("frequency.hi", panel_.hi);
    v.number("frequency.visualize", panel_.visualize);
}

bool FrequencyTool::show_figure(const Operation& op) {
    if (!is_operation<SpectrumOptions>(op)) return false;
    SpectrumOptions o = options_of<SpectrumOptions>(op);
    if (o.band) {
        panel_.lo = int(o.band->first);
        panel_.hi = int(o.band->second);
    }
    o.band.reset();  // the panel's band is its sliders
    set_options(panel_.op, o);
    panel_.open = true;
    return true;
}

VertexColors FrequencyTool::field_colors(const HalfedgeMesh& mesh) const {
    if (context_.view.settings.coloring == VertexColoring::GeodesicDistance) {
        // A mesh that carries its distances ("v:distance", written by trilab-cli geodesic)
        // shows them; otherwise the distance from the picks, once measured on this state.
        if (mesh.has_vertex_property("v:distance"))
            return color_vertices(mesh, VertexColoring::GeodesicDistance,
                                  context_.view.settings.coloring_options);
        const PickSet& picks = context_.session.picking().picks();
        if (picks.distances.size() != mesh.vertices_size() ||
            picks.mesh.topology_revision() != mesh.topology_revision())
            return {};
        return color_field(mesh, picks.distances, VertexColoring::GeodesicDistance,
                           context_.view.settings.coloring_options);
    }
    if (context_.view.settings.coloring == VertexColoring::SurfaceDistance)
        return {};  // the Compare tool's
    const FrequencyDocument& doc = context_.session.document().frequency;
    const auto& d = doc.decomposition;
    if (!d || mesh.vertices_size() != d->base_positions.size() || d->empty()) return {};
    const FrequencyPanelState& s = panel_;
    const std::size_t last = d->size() - 1;
    const VertexColoring coloring = context_.view.settings.coloring;
    if (coloring == VertexColoring::RemovedBelow || coloring == VertexColoring::RemovedAbove) {
        // What the current entry changed, split at the top of the band: below it is shape,
        // above it detail and noise (core/algorithms/transfer_function.h).
        const std::vector<Point> before = context_.session.editing().reference_positions();
        if (before.size() != mesh.vertices_size()) return {};
        const std::size_t split = std::min(std::size_t(std::max(s.hi, 0)) + 1, d->size());
        try {
            const ChangeByFrequency change =
                change_by_frequency(*d, before, mesh.positions(), split);
            return color_field(
                mesh, coloring == VertexColoring::RemovedBelow ? change.below : change.above,
                coloring, context_.view.settings.coloring_options);
        } catch (const std::exception&) {
            return {};  // e.g. a decomposition of the largest end: the notice says what is needed
        }
    }
    const std::vector<double> values =
        context_.view.settings.coloring == VertexColoring::Frequency
            ? frequency_field(*d, std::min(std::size_t(std::max(s.visualize, 0)), last))
            : band_magnitude_field(*d, std::min(std::size_t(std::max(s.lo, 0)), last),
                                   std::min(std::size_t(std::max(s.hi, 0)), last),
                                   BandRest::Include);
    return color_field(mesh, values, context_.view.settings.coloring,
                       context_.view.settings.coloring_options);
}

}  // namespace trilab::viewer
