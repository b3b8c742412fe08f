// Set-up triangles kept from one pass of a frame for the next (Renderer): a scene drawn once for
// the ambient pass and once for each light need not be set up each time. The renderer finds the
// draws that repeat by itself; the callers only draw (the draw contract of gl/pipeline.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "gl/render_state.h"
#include "gl/triangle_setup.h"
#include "gl/vertex.h"

namespace shadowref {

// A draw's vertex and index arrays as the renderer saw them: where they were and how long.
struct SetupReuseKey {
  const ClipVertex* vertices = nullptr;
  size_t vertexCount = 0;
  const uint32_t* indices = nullptr;
  size_t indexCount = 0;
  bool operator==(const SetupReuseKey&) const = default;
};

struct SetupReuseKeyHash {
  size_t operator()(const SetupReuseKey& k) const {
    size_t h = std::hash<const void*>()(k.vertices);
    for (const size_t part : {k.vertexCount, std::hash<const void*>()(k.indices), k.indexCount})
      h = h * 0x9e3779b97f4a7c15ull + part;
    return h;
  }
};

// The setups of one draw, kept by the renderer for a later draw of the same arrays: a scene's
// instances are drawn once for the ambient pass and once for each light, with the same vertices,
// indices and everything that sets a triangle up — only the depth, stencil and blend tests and
// the shader change. A later draw takes them instead of assembling again when
//  - its arrays are the same (address and length: a setup points at its vertices, whose varyings
//    the fragments read when they are shaded — a Gouraud pass's colours change from pass to pass),
//  - the clip positions of its vertices and its indices are byte for byte those the setups were
//    made from (a copy is kept: the draw contract lets the caller change its arrays between
//    passes, and a position compared by value would take -0.0 for 0.0),
//  - its state sets triangles up alike (setsUpAlike).
// Setups are a function of these alone, so the same setups, the same bytes. A draw that clipped a
// triangle keeps nothing: the vertices clipping makes (their varyings interpolated then) last only
// until its flush. One draw per flush keeps or takes an entry, and only a draw with a shader
// (Renderer::claimReuse).
class SetupReuse {
 public:
  bool holdsSetups() const { return kept_; }

 private:
  friend class Renderer;
  // Whether the call's positions and indices are byte for byte the ones kept.
  bool sameContents(std::span<const ClipVertex> vertices, std::span<const uint32_t> indices) const;
  void keepContents(std::span<const ClipVertex> vertices, std::span<const uint32_t> indices);

  bool kept_ = false;
  uint64_t claimFlush_ = UINT64_MAX;  // the flush in which a draw has it (one draw per flush keeps or takes)
  std::vector<glm::dvec4> positions_;  // the clip positions the setups were made from
  std::vector<uint32_t> indices_;      // and the indices
  RenderState state_;
  std::vector<const TriangleSetup*> setups_;
  std::vector<SetupBounds> bounds_;
  uint64_t culled_ = 0;
  int minY_ = 0, maxY_ = -1;
  std::vector<std::shared_ptr<const SetupBlock>> blocks_;  // where setups_ point
};

// Whether two states set a draw's triangles up alike: the same clipping, window transform,
// facing, culling and depth offset (the tests, masks, blending and scissor do not enter a setup).
bool setsUpAlike(const RenderState& a, const RenderState& b);

}  // namespace shadowref
