// Byte-for-byte comparison of two rendered frames: every buffer (floats by their bits, not their
// values), the per-light stencil copies and the fragment counters.
#pragma once

#include "shadow/frame_renderer.h"

namespace shadowref::testing {

void requireIdenticalFrames(const FrameResult& a, const FrameResult& b);

}  // namespace shadowref::testing
