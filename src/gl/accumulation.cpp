#include "gl/accumulation.h"

#include <algorithm>

#include "gl/clear.h"
#include "gl/fragment_ops.h"

namespace shadowref {

const char* name(AccumOp op) {
  switch (op) {
    case AccumOp::Accum: return "ACCUM";
    case AccumOp::Load: return "LOAD";
    case AccumOp::Return: return "RETURN";
    case AccumOp::Mult: return "MULT";
    case AccumOp::Add: return "ADD";
  }
  return "?";
}

void accumulate(Framebuffer& fb, const RenderState& state, AccumOp op, float value) {
  fb.ensureAccum();
  if (op == AccumOp::Accum || op == AccumOp::Load || op == AccumOp::Return) fb.ensureColor();
  const Rect r = clearRegion(fb, state);
  for (int y = r.y; y < r.y + r.height; ++y) {
    for (int x = r.x; x < r.x + r.width; ++x) {
      const size_t i = fb.index(x, y);
      glm::vec4& acc = fb.accum()[i];
      switch (op) {
        case AccumOp::Accum: acc += value * fb.color()[i]; break;
        case AccumOp::Load: acc = value * fb.color()[i]; break;
        case AccumOp::Return:
          fb.color()[i] = writeColor(fb.color()[i], glm::dvec4(value * acc), state.colorMask);
          break;
        case AccumOp::Mult: acc *= value; break;
        case AccumOp::Add: acc += glm::vec4(value); break;
      }
    }
  }
}

}  // namespace shadowref
