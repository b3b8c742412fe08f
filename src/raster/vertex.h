// What the primitive stages consume: homogeneous clip-space positions plus varyings.
#pragma once

#include <array>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace shadowref {

// Varyings are interpolated perspective-correctly across a triangle. Double precision: they
// carry world positions for lighting and shadow-map lookups, where float would be the error.
inline constexpr int kMaxVaryings = 16;

struct ClipVertex {
  glm::dvec4 position{0.0};  // clip space; w = 0 (a point at infinity) is legal
  std::array<double, kMaxVaryings> varyings{};
};

// An allocator whose resize() and emplace_back() leave the new elements unconstructed, for
// aggregates that are written whole right after (vertices filled in ranges by the threads, triangle
// setups): std::vector would first zero every element, a 160-byte vertex or 296-byte setup, the
// vertices all on the calling thread. The storage's objects of such (implicit-lifetime) types exist
// from allocation; whoever fills an element writes all of it before anything reads it.
template <class T>
struct ConstructLaterAllocator : std::allocator<T> {
  using std::allocator<T>::allocator;
  template <class U>
  struct rebind {
    using other = ConstructLaterAllocator<U>;
  };
  template <class U>
  void construct(U*) noexcept {}
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// Vertices filled after allocation, range by range (prepareInstances, the Gouraud passes' lit copies).
using ClipVertexBuffer = std::vector<ClipVertex, ConstructLaterAllocator<ClipVertex>>;

// Constructs the vertex at `slot` of a ClipVertexBuffer as a copy of `v`.
inline ClipVertex& placeVertex(ClipVertex& slot, const ClipVertex& v) {
  return *::new (static_cast<void*>(&slot)) ClipVertex(v);
}

}  // namespace shadowref
