// Render state as plain data (OpenGL 2.1 fixed-function semantics, [GL 2.1]).
// Everything the per-fragment operations and the primitive stages consult lives here, so a
// draw is fully described by (state, vertices, shader) and can be printed or compared.
#pragma once

#include <array>
#include <cstdint>

namespace shadowref {

enum class CompareFunc : uint8_t { Never, Less, Equal, LEqual, Greater, NotEqual, GEqual, Always };

enum class StencilOp : uint8_t { Keep, Zero, Replace, Incr, Decr, Invert, IncrWrap, DecrWrap };

enum class BlendFactor : uint8_t {
  Zero, One, SrcColor, OneMinusSrcColor, DstColor, OneMinusDstColor,
  SrcAlpha, OneMinusSrcAlpha, DstAlpha, OneMinusDstAlpha
};

enum class CullMode : uint8_t { None, Front, Back, FrontAndBack };
enum class FrontFace : uint8_t { CCW, CW };

// Which face a triangle turned out to be; indexes RenderState::stencil (two-sided stencil).
enum Facing : uint8_t { FrontFacing = 0, BackFacing = 1 };

struct StencilFaceState {
  CompareFunc func = CompareFunc::Always;
  int ref = 0;                 // clamped to [0, 255] when used, as GL does
  uint8_t mask = 0xFF;         // applied to ref and to the stored value before comparing
  uint8_t writeMask = 0xFF;
  StencilOp sfail = StencilOp::Keep;   // stencil test failed
  StencilOp dpfail = StencilOp::Keep;  // stencil passed, depth failed
  StencilOp dppass = StencilOp::Keep;  // both passed (or no depth test)
};

struct BlendState {
  bool enabled = false;
  BlendFactor src = BlendFactor::One;
  BlendFactor dst = BlendFactor::Zero;  // equation is always FUNC_ADD
};

// GL 1.1 polygon offset for filled primitives: o = factor * m + units * r ([GL 2.1, §3.5.5]).
struct PolygonOffset {
  bool enabled = false;
  double factor = 0.0;
  double units = 0.0;
};

struct Rect {
  int x = 0, y = 0, width = 0, height = 0;
};

struct Viewport {
  int x = 0, y = 0, width = 0, height = 0;
  double nearVal = 0.0, farVal = 1.0;  // glDepthRange
};

struct RenderState {
  Viewport viewport;
  bool scissorTest = false;
  Rect scissor;

  CullMode cull = CullMode::None;
  FrontFace frontFace = FrontFace::CCW;

  bool depthTest = false;
  CompareFunc depthFunc = CompareFunc::Less;
  bool depthWrite = true;
  // ARB_depth_clamp: near and far clipping off, fragment depth clamped to the depth range.
  bool depthClamp = false;
  // Clip against the far plane z <= w. Off for the infinite projection P_inf ([Kuhn 2016, §3.3]),
  // where w = 0 vertices lie exactly on it.
  bool clipFar = true;
  PolygonOffset polygonOffset;

  bool stencilTest = false;
  std::array<StencilFaceState, 2> stencil{};  // [FrontFacing], [BackFacing]

  BlendState blend;
  std::array<bool, 4> colorMask{true, true, true, true};
};

const char* name(CompareFunc f);
const char* name(StencilOp op);

}  // namespace shadowref
