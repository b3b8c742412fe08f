// The accumulation buffer operations of glAccum ([GL 2.1, §4.2.4]; [Hempe 2004, §4.2.2]). The
// operations read and write whole pixels of the colour buffer, limited by the scissor box; RETURN
// writes through the colour mask and clamps like any colour write.
#pragma once

#include "gl/framebuffer.h"
#include "gl/render_state.h"

namespace shadowref {

enum class AccumOp { Accum, Load, Return, Mult, Add };

const char* name(AccumOp op);

// ACCUM: acc += value * colour; LOAD: acc = value * colour; RETURN: colour = value * acc;
// MULT: acc *= value; ADD: acc += value.
void accumulate(Framebuffer& fb, const RenderState& state, AccumOp op, float value);

}  // namespace shadowref
