// The per-fragment path of one draw: depth and varyings at the pixel centre, then the GL
// operations of fragment_ops.h in order, then the writes. Colour work (shading, blending) is done
// only for fragments that survive the stencil and depth tests and only when colour is written at
// all, so stencil-only passes (shadow volumes) never shade.
#pragma once

#include "raster/fragment_observer.h"
#include "raster/fragment_shader.h"
#include "raster/framebuffer.h"
#include "raster/raster_stats.h"
#include "raster/render_state.h"
#include "raster/triangle_setup.h"

namespace shadowref {

struct PixelWatch {
  int x = -1, y = -1;
  FragmentObserver* observer = nullptr;
  uint64_t drawIndex = 0;
  uint32_t drawTag = 0;
};

class FragmentProcessor {
 public:
  FragmentProcessor(Framebuffer& fb, const RenderState& state, const FragmentShader* shader,
                    RasterStats& stats, const PixelWatch* watch);

  void process(const TriangleSetup& t, int x, int y, int64_t e0, int64_t e1, int64_t e2) {
    if (watch_ && watch_->observer && x == watch_->x && y == watch_->y) [[unlikely]]
      processImpl<true>(t, x, y, e0, e1, e2);
    else
      processImpl<false>(t, x, y, e0, e1, e2);
  }

 private:
  // One body for both paths; the watched one also records a FragmentEvent (pixel history).
  template <bool Watched>
  void processImpl(const TriangleSetup& t, int x, int y, int64_t e0, int64_t e1, int64_t e2);
  double fragmentDepth(const TriangleSetup& t, int x, int y) const;
  void interpolateVaryings(const TriangleSetup& t, int64_t e0, int64_t e1, int64_t e2, double* out) const;
  glm::dvec4 shade(const TriangleSetup& t, int x, int y, double z, int64_t e0, int64_t e1, int64_t e2) const;

  Framebuffer& fb_;
  const RenderState& state_;
  const FragmentShader* shader_;
  RasterStats& stats_;
  const PixelWatch* watch_;
  bool writesColor_, usesDepth_, writesDepth_, usesStencil_;
  int varyingCount_;
  double depthLo_, depthHi_;
};

}  // namespace shadowref
