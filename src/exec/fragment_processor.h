// The per-fragment path of one draw: depth and varyings at the pixel centre, then the GL
// operations of fragment_ops.h in order, then the writes. Colour work (shading, blending) is done
// only for fragments that survive the stencil and depth tests and only when colour is written at
// all, so stencil-only passes (shadow volumes) never shade.
//
// A draw's triangles go through one span kernel, the first row of the dispatch table
// (FragmentProcessor::kernelTable) whose condition the draw's state meets. Each row names the
// reference function it reproduces byte for byte: processFragment (gl/per_fragment.h) at every
// covered pixel (gl/coverage.h), the one-fragment path (process) that the watched pixel takes.
// Stencil counting (volume passes: no colour, no depth write, stencil ALWAYS with KEEP / INCR_WRAP
// / DECR_WRAP), depth only (shadow maps) and one constant colour (the ambient pass) walk each
// triangle's rows straight to the buffers, eight pixels per step; a row's last pixels are one more
// step of eight whose lanes outside the span store back what they read. Every other state goes
// row span by row span in chunks: the depth codes of the chunk first, then the tests (a chunk the
// stencil test discards whole, where failing writes nothing, is only counted); the surviving
// fragments wait, row after row, until a batch of them is full or the triangle ends, and are
// shaded and written together. Each pixel is changed at most once per triangle, so the order of
// a triangle's writes changes no byte. The watched pixel (pixel history) always takes the
// one-fragment path, which records every step; the rest of its triangle takes the chunked path.
#pragma once

#include <span>
#include <vector>

#include "gl/coverage.h"
#include "gl/fragment_observer.h"
#include "gl/fragment_shader.h"
#include "gl/framebuffer.h"
#include "gl/per_fragment.h"
#include "gl/raster_stats.h"
#include "gl/render_state.h"
#include "gl/triangle_setup.h"

namespace shadowref {

// What the span loops reuse from triangle to triangle instead of allocating: owned by the
// executor (Renderer: one per thread of its pool) and handed to each processor, so that two
// processors running at once never share one. Its contents are remade for every triangle that uses
// them: they carry nothing from one triangle to the next, and no byte depends on which thread's
// scratch a triangle used.
struct alignas(64) SpanScratch {
  std::vector<double> columnDepthParts;  // the depths' column parts of one triangle (fragment_processor.cpp)
};

// The reference definition of a fragment, the signature of processFragment (gl/per_fragment.h):
// what every span kernel reproduces at each covered pixel.
using FragmentDefinition = void (*)(Framebuffer& fb, const RenderState& state, const FragmentShader* shader,
                                    const BufferUse& use, const TriangleSetup& t, const CoveredPixel& p,
                                    RasterStats& stats, const PixelWatch* watch);

// What the dispatch table's conditions read of a draw, worked out once per draw.
struct DrawTraits {
  BufferUse use;
  bool constantColor = false;  // the shader gives every fragment one colour (FragmentShader::constantColor)
  bool blends = false;         // blending is on
  bool allChannels = false;    // the colour mask writes every channel
  bool stencilAdds = false;    // for both facings the stencil test always passes, the write mask is
                               // full and the depth ops add 0, 1 or 255 modulo 256 (KEEP, INCR_WRAP, DECR_WRAP)
};
DrawTraits drawTraits(const Framebuffer& fb, const RenderState& state, const FragmentShader* shader);

class FragmentProcessor {
 public:
  // The one-fragment definition: process() calls it, and every row of the dispatch table names it.
  static constexpr FragmentDefinition kDefinition = &processFragment;

  // A row of the dispatch table: the condition on the draw's state it applies to (in words and as
  // a predicate), the kernel that draws a triangle's pixels inside a region, and the reference
  // function whose bytes, counters included, the kernel reproduces at every covered pixel.
  struct KernelEntry {
    const char* name;        // the kernel's
    const char* condition;   // appliesTo, in words
    bool (*appliesTo)(const DrawTraits& traits);
    void (FragmentProcessor::*kernel)(const TriangleSetup& t, const Rect& region);
    const char* reproduces;  // the reference function's name
    FragmentDefinition reference;
  };
  // The dispatch table: a draw takes its first row whose condition holds; the last row holds for
  // every state.
  static std::span<const KernelEntry> kernelTable();
  static const KernelEntry& kernelFor(const DrawTraits& traits);

  FragmentProcessor(Framebuffer& fb, const RenderState& state, const FragmentShader* shader,
                    RasterStats& stats, const PixelWatch* watch, SpanScratch& scratch);

  // One fragment through the reference's per-fragment operations (gl/per_fragment.h,
  // processFragment), with the pixel history's event at the watched pixel: the definition that the
  // span loops reproduce.
  void process(const TriangleSetup& t, int x, int y, int64_t e0, int64_t e1, int64_t e2);

  // Every covered pixel of the triangle inside `region`, row by row, by the draw's kernel (the
  // general one where the watched pixel is in the triangle's bounds).
  void processTriangle(const TriangleSetup& t, const Rect& region);
  // The row of the dispatch table this draw's triangles take.
  const KernelEntry& kernel() const { return *kernel_; }

  // Every pixel of row y from xl to xr (inclusive); e holds the unbiased edge values at (xl, y).
  void processSpan(const TriangleSetup& t, int y, int xl, int xr, const int64_t e[3]);

  // Whether fragments drawn in `state` with `shader` do nothing but add 0, 1 or 255 modulo 256 to
  // the stencil (the shadow volumes' counting: the test always passes, every op KEEP, INCR_WRAP or
  // DECR_WRAP, no colour or depth written). Such draws give the same bytes in any order.
  static bool onlyAddsToStencil(const Framebuffer& fb, const RenderState& state, const FragmentShader* shader);
  // For such a state: add the counts to `stencil` (laid out as the framebuffer's stencil) instead
  // of the framebuffer's stencil buffer; the depth buffer is still the framebuffer's.
  void countInto(uint8_t* stencil) { countTarget_ = stencil; }

 private:
  static constexpr int kChunk = 64;
  static_assert(kChunk <= kMaxBatch, "a chunk's survivors are shaded as one batch");
  static const KernelEntry kKernels[];

  // The general kernel: row spans in chunks (queueSpan), then the batch still waiting.
  void spanTriangle(const TriangleSetup& t, const Rect& region);
  // processSpan without shading what waits (the rows of processTriangle's general path).
  void queueSpan(const TriangleSetup& t, int y, int xl, int xr, const int64_t e[3]);
  void runSpan(const TriangleSetup& t, int y, int xl, int xr, const int64_t e[3]);
  void depthCodes(const TriangleSetup& t, int y, int x, int n, uint32_t* codes) const;
  void countTriangle(const TriangleSetup& t, const Rect& region);
  void depthTriangle(const TriangleSetup& t, const Rect& region);
  void constantColorTriangle(const TriangleSetup& t, const Rect& region);
  void generalChunk(const TriangleSetup& t, int y, int x, int n, const uint32_t* codes, int xl, const int64_t e[3]);
  int testChunk(const TriangleSetup& t, size_t at, int n, const uint32_t* codes, int* survivors);
  int filterChunk(const StencilFaceState& face, size_t at, int n, const uint32_t* codes, int* survivors);
  // Fragments of one triangle to shade together: pixels, depths and perspective weights.
  struct Shading {
    int count = 0;
    int x[kMaxBatch], y[kMaxBatch];
    double depth[kMaxBatch], b0[kMaxBatch], b1[kMaxBatch], b2[kMaxBatch];
  };
  template <class Offset>
  void shadeAndWrite(const TriangleSetup& t, const Shading& f, glm::vec4* color, const Offset* offsets);
  // Shades the waiting survivors as one batch and writes their colours.
  void shadeWaiting();
  template <class Offset>
  void writeColors(glm::vec4* color, const Offset* offsets, int count, const glm::dvec4* shaded) const;


  Framebuffer& fb_;
  const RenderState& state_;
  const FragmentShader* shader_;
  RasterStats& stats_;
  const PixelWatch* watch_;
  SpanScratch& scratch_;
  bool writesColor_, usesDepth_, writesDepth_, usesStencil_;
  int varyingCount_;
  double depthLo_, depthHi_;
  const KernelEntry* kernel_;
  const glm::dvec4* constantColor_ = nullptr;  // the shader's colour when it has only one
  uint8_t* countTarget_ = nullptr;  // countInto's buffer; nullptr: the framebuffer's stencil
  // Per facing: whether a fragment that fails the stencil test changes nothing (the test can fail
  // and its fail op writes nothing). A chunk of such fragments that all fail — a lit pass's "equal
  // to 0" over a shadowed stretch — is counted and skipped before its depths are made: GL discards
  // a fragment that fails the stencil test before the depth test ([GL 2.1, §4.1.5]), so its depth
  // code, depth test and shading would be thrown away.
  bool discardsUnchanged_[2] = {false, false};

  // The surviving fragments of the current triangle's chunks that wait to be shaded: a chunk of a
  // row span holds about 15 of them on average in a frame of small triangles (the outdoor scene's
  // camera pass), where shading, lookups and writes cost nearly as much per call as per fragment. Their
  // weights are the chunk's (generalChunk), their order the rows', and they are shaded before the
  // triangle's rows end (shadeWaiting).
  struct Waiting : Shading {
    const TriangleSetup* triangle = nullptr;
    size_t at[kMaxBatch];  // buffer index
  };
  Waiting waiting_;
};

}  // namespace shadowref
