#include "gl/render_state.h"

namespace shadowref {

const char* name(CompareFunc f) {
  switch (f) {
    case CompareFunc::Never: return "NEVER";
    case CompareFunc::Less: return "LESS";
    case CompareFunc::Equal: return "EQUAL";
    case CompareFunc::LEqual: return "LEQUAL";
    case CompareFunc::Greater: return "GREATER";
    case CompareFunc::NotEqual: return "NOTEQUAL";
    case CompareFunc::GEqual: return "GEQUAL";
    case CompareFunc::Always: return "ALWAYS";
  }
  return "?";
}

const char* name(StencilOp op) {
  switch (op) {
    case StencilOp::Keep: return "KEEP";
    case StencilOp::Zero: return "ZERO";
    case StencilOp::Replace: return "REPLACE";
    case StencilOp::Incr: return "INCR";
    case StencilOp::Decr: return "DECR";
    case StencilOp::Invert: return "INVERT";
    case StencilOp::IncrWrap: return "INCR_WRAP";
    case StencilOp::DecrWrap: return "DECR_WRAP";
  }
  return "?";
}

}  // namespace shadowref
