#pragma once
// Strongly typed element handles: plain 32-bit indices, one distinct type per element kind.
// A handle carries no mesh pointer, so copying a mesh (a snapshot) needs no handle fix-ups.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>

namespace trilab {

using Index = std::uint32_t;
inline constexpr Index kInvalidIndex = std::numeric_limits<Index>::max();

template <class Tag>
class Handle {
public:
    constexpr Handle() = default;
    constexpr explicit Handle(Index idx) : idx_(idx) {}
    constexpr Index idx() const { return idx_; }
    constexpr bool is_valid() const { return idx_ != kInvalidIndex; }
    friend constexpr bool operator==(Handle a, Handle b) { return a.idx_ == b.idx_; }
    friend constexpr bool operator!=(Handle a, Handle b) { return a.idx_ != b.idx_; }
    friend constexpr bool operator<(Handle a, Handle b) { return a.idx_ < b.idx_; }

private:
    Index idx_ = kInvalidIndex;
};

struct VertexTag {};
struct HalfedgeTag {};
struct EdgeTag {};
struct FaceTag {};

using Vertex = Handle<VertexTag>;
using Halfedge = Handle<HalfedgeTag>;
using Edge = Handle<EdgeTag>;
using Face = Handle<FaceTag>;

}  // namespace trilab

template <class Tag>
struct std::hash<trilab::Handle<Tag>> {
    std::size_t operator()(trilab::Handle<Tag> h) const noexcept {
        return std::hash<trilab::Index>()(h.idx());
    }
};
