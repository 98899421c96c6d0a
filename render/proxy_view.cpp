#include "render/proxy_view.h"

#include <string>

#include "core/errors.h"

namespace trilab {

bool MotionClock::frame(const glm::mat4& view, const glm::mat4& projection, double now) {
    const bool changed = has_camera_ && (view != view_ || projection != projection_);
    has_camera_ = true;
    view_ = view;
    projection_ = projection;
    if (changed) last_motion_ = now;
    return changed;
}

VertexColors sample_proxy_colors(const VertexColors& colors,
                                 const std::vector<Index>& representative) {
    VertexColors out;
    out.range = colors.range;
    out.kind = colors.kind;
    out.label = colors.label;
    out.has_legend = colors.has_legend;
    out.categories = colors.categories;
    if (colors.colors.empty()) return out;
    const bool values = !colors.values.empty();
    out.colors.reserve(representative.size());
    if (values) out.values.reserve(representative.size());
    for (Index r : representative) {
        if (r >= colors.colors.size() || (values && r >= colors.values.size()))
            throw InvalidArgument("sample_proxy_colors: representative " + std::to_string(r) +
                                  " outside the " + std::to_string(colors.colors.size()) +
                                  " colours");
        out.colors.push_back(colors.colors[r]);
        if (values) out.values.push_back(colors.values[r]);
    }
    return out;
}

std::vector<float> sample_proxy_selection(const std::vector<float>& weights,
                                          const std::vector<Index>& representative) {
    std::vector<float> out;
    out.reserve(representative.size());
    for (Index r : representative) {
        if (r >= weights.size())
            throw InvalidArgument("sample_proxy_selection: representative " + std::to_string(r) +
                                  " outside the " + std::to_string(weights.size()) + " weights");
        out.push_back(weights[r]);
    }
    return out;
}

std::vector<TexCoord> sample_proxy_texcoords(const HalfedgeMesh& mesh,
                                             const std::vector<Index>& representative) {
    const auto vertex_uv = mesh.get_vertex_property<TexCoord>("v:texcoord");
    const auto corner_uv = mesh.get_halfedge_property<TexCoord>("h:texcoord");
    std::vector<TexCoord> out;
    if (!vertex_uv && !corner_uv) return out;
    out.reserve(representative.size());
    for (Index r : representative) {
        if (r >= mesh.vertices_size())
            throw InvalidArgument("sample_proxy_texcoords: representative " + std::to_string(r) +
                                  " outside the " + std::to_string(mesh.vertices_size()) +
                                  " vertices");
        const Vertex v(r);
        if (vertex_uv) {
            out.push_back(vertex_uv[v]);
            continue;
        }
        // A corner at v: the halfedge into v from its outgoing halfedge's twin, which lies in
        // a face (halfedge(v) is the boundary one at a boundary vertex).
        const Halfedge out_h = mesh.halfedge(v);
        out.push_back(out_h.is_valid() ? corner_uv[HalfedgeMesh::twin(out_h)] : TexCoord::Zero());
    }
    return out;
}

RenderStyle stand_in_style(RenderStyle style) {
    style.facing_normals = true;
    return style;
}

double proxy_error_pixels(double error_bound, const Camera& camera, float framebuffer_scale) {
    return error_bound * double(camera.pixels_per_unit()) * double(framebuffer_scale);
}

}  // namespace trilab
