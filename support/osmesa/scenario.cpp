#include "osmesa/scenario.h"

namespace shadowref::conformance {

RenderState fullViewportState(int width, int height) {
  RenderState s;
  s.viewport = Viewport{0, 0, width, height, 0.0, 1.0};
  s.scissor = Rect{0, 0, width, height};
  return s;
}

}  // namespace shadowref::conformance
