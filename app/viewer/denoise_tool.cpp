#include "app/viewer/denoise_tool.h"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

#include "app/viewer/panel_helpers.h"
#include "app/viewer/widgets.h"
#include "core/errors.h"

namespace trilab::viewer {

using namespace ui;

BandEnergies band_energies(const SpectralDecomposition& d, const std::vector<Point>& before,
                           const std::vector<Point>& after, std::size_t bands) {
    const std::size_t n = d.base_positions.size();
    if (before.size() != n || after.size() != n)
        throw InvalidArgument("band_energies: expected " + std::to_string(n) +
                              " positions (the decomposed mesh's vertices), got " +
                              std::to_string(before.size()) + " and " +
                              std::to_string(after.size()));
    if (bands == 0) throw InvalidArgument("band_energies: bands must be at least 1");
    BandEnergies e;
    const std::size_t k = d.size();
    const std::size_t count = std::min(bands, k);
    for (std::size_t b = 0; b < count; ++b) {
        e.lo.push_back(b * k / count);
        e.hi.push_back((b + 1) * k / count - 1);
    }
    e.rest = k < d.rows();
    for (const std::vector<Point>* p : {&before, &after}) {
        // α = Eᵀ·S·X over the rows, X gathered through the decomposition's map.
        Eigen::MatrixXd sx(Eigen::Index(d.rows()), 3);
        double total = 0;
        for (std::size_t r = 0; r < d.rows(); ++r) {
            const Point& x = (*p)[d.map.vertex_of[r].idx()];
            sx.row(Eigen::Index(r)) = d.S(Eigen::Index(r)) * x.transpose();
            total += d.S(Eigen::Index(r)) * x.squaredNorm();
        }
        const Eigen::MatrixXd alpha = d.eigenvectors.transpose() * sx;
        std::vector<double>& out = p == &before ? e.before : e.after;
        double computed = 0;
        for (std::size_t b = 0; b < count; ++b) {
            double sum = 0;
            for (std::size_t i = e.lo[b]; i <= e.hi[b]; ++i)
                sum += alpha.row(Eigen::Index(i)).squaredNorm();
            out.push_back(sum);
            computed += sum;
        }
        if (e.rest) out.push_back(std::max(0.0, total - computed));
    }
    if (e.rest) {
        e.lo.push_back(k);
        e.hi.push_back(d.rows() - 1);
    }
    return e;
}

DenoiseTool::DenoiseTool(ViewerContext& context) : OperationTool(context, {}) {
    set_panels({&panel_});
}

void DenoiseTool::update() {
    OperationTool::update();
    update_bands();
}

void DenoiseTool::update_bands() {
    // O(k · rows) on a worker thread, from copies of the positions and a share of the
    // decomposition; only while the section shows them (opening it computes them for the
    // preview shown then).
    if (bands_job_.valid() &&
        bands_job_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        try {
            bands_ = bands_job_.get();
            ++computations_;
        } catch (const std::exception& e) {
            context_.session.log().warning(std::string("Denoise: band energies: ") + e.what());
        }
    }
    if (!panel_.open || bands_job_.valid()) return;  // one computation at a time
    const Session& session = context_.session;
    const std::optional<Operation>& requested = session.previews().requested();
    const OperationResult* preview =
        requested && requested->def == panel_.op.def ? session.previews().result() : nullptr;
    const HalfedgeMesh* after =
        preview && !preview->steps.empty() ? &preview->steps.back().mesh : nullptr;
    const FrequencyDocument& f = session.document().frequency;
    const HalfedgeMesh& mesh = session.mesh();
    char key[160];
    std::snprintf(key, sizeof key, "%p %p %p %llu", static_cast<const void*>(preview),
                  static_cast<const void*>(f.decomposition.get()), static_cast<const void*>(&mesh),
                  static_cast<unsigned long long>(mesh.geometry_revision()));
    if (bands_key_ == key) return;
    bands_key_ = key;
    bands_ = BandEnergies{};
    if (!after || !f.valid || !f.decomposition || f.decomposition->empty()) return;
    const std::size_t n = f.decomposition->base_positions.size();
    if (mesh.vertices_size() != n || after->vertices_size() != n) return;
    bands_job_ = std::async(std::launch::async, [d = f.decomposition, before = mesh.positions(),
                                                 now = after->positions()] {
        return band_energies(*d, before, now, kBands);
    });
}

void DenoiseTool::finish() {
    if (bands_job_.valid()) bands_job_.wait();
    update_bands();
}

namespace {

/// Two bars per band, log10 of the energy: the document's (grey) and the preview's (orange).
/// Test hook ids: "denoise: bands", "denoise: band B".
void band_plot(const BandEnergies& e) {
    const float width = widget_width(16.0f, 0.0f), height = 4.0f * ImGui::GetFrameHeight();
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::Dummy(ImVec2(width, height));
    note_widget("denoise: bands");
    double lo = 1e300, hi = -1e300;
    for (const std::vector<double>* v : {&e.before, &e.after})
        for (double x : *v)
            if (x > 0) {
                lo = std::min(lo, std::log10(x));
                hi = std::max(hi, std::log10(x));
            }
    if (!(hi >= lo)) return;
    lo = std::floor(lo) - 0.5;
    hi = std::ceil(hi);
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->AddRect(p0, ImVec2(p0.x + width, p0.y + height), IM_COL32(110, 110, 110, 255));
    const float slot = width / float(e.size());
    for (std::size_t b = 0; b < e.size(); ++b) {
        const float x0 = p0.x + slot * float(b);
        for (int side = 0; side < 2; ++side) {
            const double v = side == 0 ? e.before[b] : e.after[b];
            if (!(v > 0)) continue;
            const float t = float((std::log10(v) - lo) / (hi - lo));
            const float bx0 = x0 + slot * (0.15f + 0.35f * float(side));
            const ImU32 color =
                side == 0 ? IM_COL32(150, 150, 150, 255) : IM_COL32(255, 170, 60, 255);
            draw->AddRectFilled(ImVec2(bx0, p0.y + height * (1.0f - t)),
                                ImVec2(bx0 + 0.33f * slot, p0.y + height), color);
        }
        note_widget_rect("denoise: band " + std::to_string(b), x0, p0.y, x0 + slot, p0.y + height);
    }
}

}  // namespace

void DenoiseTool::section(const SidebarContext& context, CommandQueue& commands) {
    SidebarSection section("Denoise", panel_.open);
    if (!section) return;
    ImGui::TextWrapped("%s", panel_words(panel_.op.def->summary).c_str());
    operation_panel_body(panel_, "Denoise", context.busy, commands);
    ImGui::Separator();
    ImGui::TextUnformatted("Energy by frequency band");
    if (bands_.size() == 0) {
        wrapped_disabled(
            "with a frequency decomposition of this mesh (Frequency decomposition > "
            "Decompose), the preview's energy in each band against the document's");
    } else {
        band_plot(bands_);
        wrapped_disabled("grey: the document, orange: the preview");
        for (std::size_t b = 0; b < bands_.size(); ++b) {
            const bool rest = bands_.rest && b + 1 == bands_.size();
            const double ratio = bands_.before[b] > 0 ? bands_.after[b] / bands_.before[b] : 1.0;
            if (rest)
                ImGui::TextDisabled("rest (%zu-): %.3g -> %.3g (x%.3g)", bands_.lo[b],
                                    bands_.before[b], bands_.after[b], ratio);
            else
                ImGui::TextDisabled("%zu-%zu: %.3g -> %.3g (x%.3g)", bands_.lo[b], bands_.hi[b],
                                    bands_.before[b], bands_.after[b], ratio);
        }
        wrapped_disabled(
            "the denoiser keeps the high bands that carry the edges; smoothing takes them all");
    }
    ImGui::Separator();
    morph_hint();
}

PanelEntries DenoiseTool::panels() {
    PanelEntry entry;
    entry.name = "denoise";
    entry.title = "Denoise...";
    entry.open = &panel_.open;
    entry.menu = PanelMenu::Tools;
    entry.in_tools = true;
    return {entry};
}

void DenoiseTool::settings(SettingsVisitor& v) {
    // The key the generic panel saved it under before the tool had its own panel.
    operation_setting(v, "panel.tool.denoise", panel_);
}

}  // namespace trilab::viewer
