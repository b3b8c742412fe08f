// Set-up triangles kept from one pass of a frame for the next (Renderer, DrawCall::reuse): a
// scene drawn once for the ambient pass and once for each light need not be set up each time.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "gl/render_state.h"
#include "gl/triangle_setup.h"
#include "gl/vertex.h"

namespace shadowref {

// A draw's set-up triangles, kept for a later draw of the same triangles in another pass: a
// scene's instances are drawn once for the ambient pass and once for each light, with the same
// vertices, indices and everything that sets a triangle up — only the depth, stencil and blend
// tests and the shader change. The first draw given one of these assembles as usual and keeps its
// setups in it; a later draw given it takes them instead of assembling again when it draws the same
// vertex and index arrays (the same objects, whose positions and indices the caller keeps
// unchanged meanwhile; the varyings may change, as a Gouraud pass's colours do: they are read
// when fragments are shaded) in a state that sets triangles up alike (setsUpAlike), on the same
// renderer. The same setups, so the same bytes. A draw that clipped a triangle is not kept: the
// vertices clipping makes (their varyings interpolated then) last only until its flush. The
// caller owns it; it holds the setups (and the blocks they are in) until it is destroyed or kept
// anew. One draw per flush has it (keeps or takes setups).
class SetupReuse {
 public:
  bool holdsSetups() const { return kept_; }
  // Holds no setups any more, as if new, but keeps its lists' buffers: for a caller that keeps it
  // from frame to frame, drawing arrays at the same addresses (a renderer takes only setups it kept
  // itself, but one renderer may draw two frames).
  void forget() {
    kept_ = false;
    blocks_.clear();
  }

 private:
  friend class Renderer;
  bool kept_ = false;
  uint64_t renderer_ = 0;  // the serial number of the Renderer that kept the setups
  // The draw that has it in the current flush of a renderer (one draw per flush keeps or takes).
  uint64_t claimRenderer_ = 0, claimFlush_ = 0;
  const ClipVertex* vertices_ = nullptr;
  size_t vertexCount_ = 0;
  const uint32_t* indices_ = nullptr;
  size_t indexCount_ = 0;
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
