// Render states of the volume pass: how the stencil buffer counts shadow-volume faces
// ([Kuhn 2016, §3.2, §4.3.1]; [SV slides]).
//
//  - z-pass: front faces INCR where the depth test passes, back faces DECR.
//  - z-fail (Carmack's reverse [Carmack 2000]; [Everitt & Kilgard 2002]): back faces INCR where the
//    depth test fails, front faces DECR.
// Common to both: stencil test ALWAYS (only depth decides), depth func LESS, no depth writes, no
// colour writes. Wrapping ops (INCR_WRAP / DECR_WRAP, [SV slides]) let counts survive more than 255
// volumes; the saturating INCR / DECR exist to show the overflow.
//
// Either one pass with two-sided stencil (cull nothing; front and back state differ), or two
// passes with culling as [SV slides] draws them: first the faces that increment, then the faces
// that decrement. The increment pass goes first so saturating DECR cannot clamp at 0 before the
// matching INCR arrived.
#pragma once

#include <vector>

#include "gl/render_state.h"

namespace shadowref {

enum class StencilCounting : uint8_t { ZPass, ZFail };

struct CountingOptions {
  bool twoSided = true;  // ShadowSettings::twoSidedStencil
  bool wrap = true;      // ShadowSettings::wrapOps
};

// The states to draw the volumes with, in order: one (two-sided) or two (culled passes). Each is
// `base` (viewport, scissor, clipping, front-face convention) with the counting fields set.
std::vector<RenderState> volumePassStates(const RenderState& base, StencilCounting counting,
                                          const CountingOptions& options = {});

// The op that counts a volume face for `counting`: which face increments, which decrements, and
// whether it happens on depth pass (z-pass) or depth fail (z-fail).
StencilFaceState countingFaceState(StencilCounting counting, Facing face, bool wrap);

const char* name(StencilCounting counting);

}  // namespace shadowref
