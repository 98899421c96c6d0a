#pragma once
// CompareTool: the Compare section (issue 40, "truth you can measure"): how far the current
// state is from another surface, vertex by vertex. The other surface is a state of the
// history (Entry N, its last step) or a mesh file; each vertex's distance to it
// (vertex_surface_distances(), mesh_distance.h: one-sided, any two meshes) is computed on a
// worker thread from copies, once per pair of states, and shown as the colouring "Distance to
// the compared surface" (Rendering > Colour by vertex, or the section's button), whose legend
// has the histogram of the values; the section gives the mean, the largest and the share of
// the diagonal. `trilab-cli compare A B` gives the same figures; `trilab-cli render A
// --color surface-distance --reference B` the same picture.
#include <array>
#include <cstdint>
#include <future>
#include <string>
#include <vector>

#include "app/viewer/tool.h"

namespace trilab::viewer {

/// The figures of a set of distances (NaN entries are skipped).
struct DistanceSummary {
    std::size_t vertices = 0;  ///< with a distance
    double mean = 0, max = 0, rms = 0;
};
DistanceSummary summarize_distances(const std::vector<double>& distances);

class CompareTool : public Tool {
public:
    explicit CompareTool(ViewerContext& context);
    void update() override;
    VertexColors field_colors(const HalfedgeMesh& mesh) const override;
    void section(const SidebarContext& context, CommandQueue& commands) override;
    PanelEntries panels() override;
    void settings(SettingsVisitor& v) override;

    enum class Source { State, File };
    struct Target {
        Source source = Source::State;
        int entry = 0;     ///< Source::State: the history entry (its last step)
        std::string file;  ///< Source::File: the mesh file
    };
    Target& target() { return target_; }
    bool& open() { return open_; }
    /// The distances of the current state to the target, once computed (empty otherwise), and
    /// their figures; `error()` says why there are none (a file that does not load).
    const std::vector<double>& distances() const { return result_.distances; }
    const DistanceSummary& summary() const { return result_.summary; }
    const std::string& error() const { return result_.error; }
    bool computing() const { return job_.valid(); }
    /// Waits for a running computation (tests).
    void finish();

private:
    struct Result {
        std::string key;  ///< the pair of states it is of
        std::vector<double> distances;
        DistanceSummary summary;
        double diagonal = 0;
        std::string error;
        std::array<std::uint64_t, 2> of{0, 0};  ///< the current state's revisions
    };
    std::string key_now() const;
    void start(const std::string& key);
    bool open_ = false;
    Target target_;
    Result result_;
    std::future<Result> job_;
    std::array<char, 512> file_text_{};  ///< the path being typed
};

}  // namespace trilab::viewer
