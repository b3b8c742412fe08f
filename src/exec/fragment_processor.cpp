#include "exec/fragment_processor.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <type_traits>
#include <vector>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "exec/clamp_unit.h"
#include "exec/compare_dispatch.h"
#include "exec/depth_lanes.h"
#include "gl/fragment_ops.h"
#include "gl/per_fragment.h"
#include "exec/rasterizer.h"

namespace shadowref {

namespace {

bool addsToStencil(const RenderState& state);

}  // namespace

FragmentProcessor::FragmentProcessor(Framebuffer& fb, const RenderState& state,
                                     const FragmentShader* shader, RasterStats& stats,
                                     const PixelWatch* watch, SpanScratch& scratch)
    : fb_(fb), state_(state), shader_(shader), stats_(stats), watch_(watch), scratch_(scratch) {
  const BufferUse use = bufferUse(fb, state, shader);
  writesColor_ = use.writesColor;
  usesDepth_ = use.usesDepth;
  writesDepth_ = use.writesDepth;
  usesStencil_ = use.usesStencil;
  varyingCount_ = shader ? shader->varyingCount() : 0;
  depthLo_ = std::min(state.viewport.nearVal, state.viewport.farVal);
  depthHi_ = std::max(state.viewport.nearVal, state.viewport.farVal);
  if (writesColor_) constantColor_ = shader->constantColor();
  kernel_ = &kernelFor(drawTraits(fb, state, shader));
  for (const Facing f : {FrontFacing, BackFacing}) {
    const StencilFaceState& face = state.stencil[f];
    discardsUnchanged_[f] = usesStencil_ && face.func != CompareFunc::Always &&
                            !stencilOpMayWrite(face.sfail, face.writeMask);
  }
}

void FragmentProcessor::process(const TriangleSetup& t, int x, int y, int64_t e0, int64_t e1, int64_t e2) {
  const BufferUse use{writesColor_, usesDepth_, writesDepth_, usesStencil_};
  kDefinition(fb_, state_, shader_, use, t, CoveredPixel{x, y, {e0, e1, e2}}, stats_, watch_);
}

namespace {

// What KEEP, INCR_WRAP and DECR_WRAP with a full write mask do to a stencil byte: add 0, 1 or 255
// modulo 256. Other ops (saturating, REPLACE, INVERT, ZERO) have no such form.
bool wrapDelta(StencilOp op, uint8_t& delta) {
  switch (op) {
    case StencilOp::Keep: delta = 0; return true;
    case StencilOp::IncrWrap: delta = 1; return true;
    case StencilOp::DecrWrap: delta = 255; return true;
    default: return false;
  }
}

}  // namespace

DrawTraits drawTraits(const Framebuffer& fb, const RenderState& state, const FragmentShader* shader) {
  DrawTraits d;
  d.use = bufferUse(fb, state, shader);
  d.constantColor = d.use.writesColor && shader->constantColor() != nullptr;
  d.blends = state.blend.enabled;
  d.allChannels = state.colorMask[0] && state.colorMask[1] && state.colorMask[2] && state.colorMask[3];
  d.stencilAdds = addsToStencil(state);
  return d;
}

namespace {
bool countsStencil(const DrawTraits& d) {
  return !d.use.writesColor && !d.use.writesDepth && d.use.usesStencil && d.stencilAdds;
}
bool depthOnly(const DrawTraits& d) { return !d.use.writesColor && !d.use.usesStencil; }
bool oneColor(const DrawTraits& d) {
  return d.use.writesColor && d.constantColor && !d.use.usesStencil && !d.blends && d.allChannels;
}
bool anyState(const DrawTraits&) { return true; }
}  // namespace

// The first three conditions exclude each other (stencil used, neither stencil nor colour, colour
// without stencil), so their order is free; the general kernel is last.
const FragmentProcessor::KernelEntry FragmentProcessor::kKernels[] = {
    {"countTriangle",
     "no colour or depth written; the stencil test on, always passing, every depth op adding 0, 1 or 255 modulo 256",
     countsStencil, &FragmentProcessor::countTriangle, "processFragment", kDefinition},
    {"depthTriangle", "no colour written and no stencil used", depthOnly, &FragmentProcessor::depthTriangle,
     "processFragment", kDefinition},
    {"constantColorTriangle",
     "one colour for every fragment, no stencil, no blending, every channel written", oneColor,
     &FragmentProcessor::constantColorTriangle, "processFragment", kDefinition},
    {"spanTriangle", "any state", anyState, &FragmentProcessor::spanTriangle, "processFragment", kDefinition},
};

std::span<const FragmentProcessor::KernelEntry> FragmentProcessor::kernelTable() { return kKernels; }

const FragmentProcessor::KernelEntry& FragmentProcessor::kernelFor(const DrawTraits& traits) {
  for (const KernelEntry& e : kKernels)
    if (e.appliesTo(traits)) return e;
  return kKernels[std::size(kKernels) - 1];  // (not reached: the last row applies to any state)
}

bool FragmentProcessor::onlyAddsToStencil(const Framebuffer& fb, const RenderState& state, const FragmentShader* shader) {
  return countsStencil(drawTraits(fb, state, shader));
}

namespace {
// Whether every fragment's stencil op, for either facing, adds 0, 1 or 255 modulo 256 whatever
// the stencil holds: the test always passes and every op is KEEP, INCR_WRAP or DECR_WRAP.
bool addsToStencil(const RenderState& state) {
  for (const StencilFaceState& s : state.stencil) {
    uint8_t delta;
    if (s.func != CompareFunc::Always || s.writeMask != 0xFF || !wrapDelta(s.dpfail, delta) || !wrapDelta(s.dppass, delta))
      return false;
  }
  return true;
}
}  // namespace

void FragmentProcessor::processSpan(const TriangleSetup& t, int y, int xl, int xr, const int64_t e[3]) {
  queueSpan(t, y, xl, xr, e);
  shadeWaiting();
}

void FragmentProcessor::queueSpan(const TriangleSetup& t, int y, int xl, int xr, const int64_t e[3]) {
  if (watch_ && watch_->observer && y == watch_->y && watch_->x >= xl && watch_->x <= xr) [[unlikely]] {
    const int wx = watch_->x;
    if (wx > xl) runSpan(t, y, xl, wx - 1, e);
    shadeWaiting();  // the pixel history sees the rest of the triangle's writes up to here
    int64_t ew[3];
    for (int i = 0; i < 3; ++i) ew[i] = e[i] + t.stepX[i] * (wx - xl);
    process(t, wx, y, ew[0], ew[1], ew[2]);
    if (wx < xr) {
      for (int i = 0; i < 3; ++i) ew[i] += t.stepX[i];
      runSpan(t, y, wx + 1, xr, ew);
    }
    return;
  }
  runSpan(t, y, xl, xr, e);
}

namespace {

// Whether none of n fragments over these stencil values passes the face's stencil test (the
// comparison of stencilTest, fixed at compile time, on bytes).
bool noneLetThrough(const StencilFaceState& face, const uint8_t* stencil, int n) {
  const uint8_t ref = uint8_t(maskedStencilReference(face)), mask = uint8_t(face.mask);
  bool none = true;
  withCompare(face.func, [&](auto f) {
    uint8_t passed = 0;
    for (int i = 0; i < n; ++i) passed |= uint8_t(passes<decltype(f)::value>(ref, uint8_t(stencil[i] & mask)));
    none = passed == 0;
  });
  return none;
}

}  // namespace

void FragmentProcessor::runSpan(const TriangleSetup& t, int y, int xl, int xr, const int64_t e[3]) {
  stats_.fragments += uint64_t(xr - xl + 1);
  const StencilFaceState& face = state_.stencil[t.facing];
  const uint8_t* const stencil = discardsUnchanged_[t.facing] ? fb_.stencil().data() + fb_.index(0, y) : nullptr;
  uint32_t codes[kChunk];
  for (int x = xl; x <= xr; x += kChunk) {
    const int n = std::min(kChunk, xr - x + 1);
    if (stencil && noneLetThrough(face, stencil + x, n)) {
      stats_.stencilFailed += uint64_t(n);
      continue;
    }
    depthCodes(t, y, x, n, codes);
    generalChunk(t, y, x, n, codes, xl, e);
  }
}

namespace {

using v4d = double __attribute__((vector_size(32)));
using v4f = float __attribute__((vector_size(16)));
using v4u = uint32_t __attribute__((vector_size(16)));
using v4b = uint8_t __attribute__((vector_size(4)));
using v8f = float __attribute__((vector_size(32)));
using v8u = uint32_t __attribute__((vector_size(32)));
using v8b = uint8_t __attribute__((vector_size(8)));
using v4i = int32_t __attribute__((vector_size(16)));
using v8i = int32_t __attribute__((vector_size(32)));

// The low byte of each lane (one byte shuffle; a converting cast is lowered lane by lane).
inline v8b lowBytes(v8u x) {
  using v32b = uint8_t __attribute__((vector_size(32)));
  v32b bytes;
  std::memcpy(&bytes, &x, sizeof bytes);
  constexpr int low = std::endian::native == std::endian::little ? 0 : 3;
  return __builtin_shufflevector(bytes, bytes, low, 4 + low, 8 + low, 12 + low, 16 + low, 20 + low, 24 + low, 28 + low);
}

// How a triangle's rows make depth codes, fixed at compile time so that the eight-pixel steps test
// nothing: Encoded, DepthCodec::encode in vector lanes (encodeLanes) for a Unorm24 buffer or after
// depth clamping (the focused trapezoidal maps);
// PlainFloat, a float32 buffer without depth clamping (the usual case), encode's clamp to [0, 1]
// in vector lanes; UnitFloat, the same where every depth of the triangle is in (0, 1]
// (TriangleSetup::depthsInUnit), so that the clamp would change nothing and is left out.
enum class RowKind { Encoded, PlainFloat, UnitFloat };

// The depth codes of a row: fragmentDepth and DepthCodec::encode with the same operations in the
// same order (planeDepthAt's sum split into its row part and its column part), eight or four
// pixels at a time, or one.
template <RowKind K>
struct RowDepth {
  static constexpr bool kPlainFloat = K != RowKind::Encoded;
  double z0, fx0, dzdx, rowPart, offset;
  const DepthCodec& codec;
  bool clamp;
  double lo, hi;  // the depth range, when clamping
  RowDepth(const TriangleSetup& t, int y, const DepthCodec& depthCodec, bool depthClamp, double depthLo, double depthHi)
      : z0(t.v[0].z), fx0(t.v[0].fx), dzdx(t.dzdx), rowPart(t.dzdy * ((double(y) + 0.5) - t.v[0].fy)),
        offset(t.depthOffset), codec(depthCodec), clamp(depthClamp), lo(depthLo), hi(depthHi) {}
  v4u codes4(int x) const {
    const v4d lane = {0.5, 1.5, 2.5, 3.5};
    return codes4(double(x) + lane);
  }
  // The depths of the four pixels whose centres' x are the lanes of cx, before the codec.
  v4d depths4(v4d cx) const { return (z0 + (dzdx * (cx - fx0) + rowPart)) + offset; }
  // The codes of the four pixels whose centres' x are the lanes of cx.
  v4u codes4(v4d cx) const { return codesOf(depths4(cx)); }
  // The codes of four depths: the depth clamp where on, then the codec.
  v4u codesOf(v4d z) const {
    if (!kPlainFloat && clamp) z = z < lo ? v4d{} + lo : (hi < z ? v4d{} + hi : z);  // std::clamp
    v4u out;
    if constexpr (K == RowKind::UnitFloat) {
      const v4f f = __builtin_convertvector(z, v4f);
      std::memcpy(&out, &f, sizeof out);
    } else if constexpr (kPlainFloat) {
      const v4f f = __builtin_convertvector(clampUnitOrZero(z), v4f);  // encode's clamp
      std::memcpy(&out, &f, sizeof out);
    } else {
      out = encodeLanes(codec, z);
    }
    return out;
  }
  // The x of eight pixel centres, kept from step to step of a row: x + 0.5 … x + 7.5, and 8 more
  // a step, are whole numbers and halves, exact in a double, so stepping gives the bits
  // double(x) + 0.5 gives (and saves a conversion and a broadcast a step). With AVX-512 a float
  // buffer's eight depths are one vector of eight doubles; otherwise two halves of four (GCC 12
  // lowers a vector of eight doubles lane by lane for AVX2).
#if defined(__AVX512F__)
  using Centres = ClampLanes8;
  static Centres centres(int x) { return double(x) + Centres{0.5, 1.5, 2.5, 3.5, 4.5, 5.5, 6.5, 7.5}; }
  static Centres nextStep(Centres c) { return c + 8.0; }
#else
  struct Centres {
    v4d low, high;
  };
  static Centres centres(int x) {
    const v4d low = double(x) + v4d{0.5, 1.5, 2.5, 3.5};
    return {low, low + 4.0};
  }
  static Centres nextStep(Centres c) { return {c.low + 8.0, c.high + 8.0}; }
#endif
  // A float buffer's codes of eight depths: the floats' bits, with encode's clamp to [0, 1] where
  // the row kind needs it — applied to the eight floats (clampUnitOrZeroFloat: the same bits as
  // clamping the doubles), one 256-bit register where the doubles are two.
  static v8u floatCodes(v8f f) {
    if constexpr (K == RowKind::PlainFloat) return std::bit_cast<v8u>(clampUnitOrZeroFloat(f));
    return std::bit_cast<v8u>(f);
  }
#if defined(__AVX512F__)
  static v8u floatCodes(ClampLanes8 z) { return floatCodes(__builtin_convertvector(z, v8f)); }
#else
  // The same from two halves of four depths.
  static v8u floatCodes(v4d low, v4d high) {
    const v4f a = __builtin_convertvector(low, v4f), b = __builtin_convertvector(high, v4f);
#if defined(__AVX__)
    return floatCodes(std::bit_cast<v8f>(_mm256_setr_m128(std::bit_cast<__m128>(a), std::bit_cast<__m128>(b))));
#else
    return floatCodes(v8f(__builtin_shufflevector(a, b, 0, 1, 2, 3, 4, 5, 6, 7)));
#endif
  }
#endif
  // The codes of the eight pixels whose centres are c.
  v8u codes8(Centres c) const {
#if defined(__AVX512F__)
    if constexpr (kPlainFloat) {
      const ClampLanes8 z = (z0 + (dzdx * (c - fx0) + rowPart)) + offset;
      return floatCodes(z);
    }
    const v4d low = {c[0], c[1], c[2], c[3]}, high = {c[4], c[5], c[6], c[7]};
    const v4u a = codes4(low), b = codes4(high);
#else
    if constexpr (kPlainFloat) return floatCodes(depths4(c.low), depths4(c.high));  // the clamp on eight floats
    const v4u a = codes4(c.low), b = codes4(c.high);
#endif
    return joined(a, b);
  }
  // Eight codes from two halves of four.
  static v8u joined(v4u a, v4u b) {
#if defined(__AVX__)
    // One insert; the generic shuffle below adds a register move per half.
    return std::bit_cast<v8u>(_mm256_setr_m128i(std::bit_cast<__m128i>(a), std::bit_cast<__m128i>(b)));
#else
    return __builtin_shufflevector(a, b, 0, 1, 2, 3, 4, 5, 6, 7);
#endif
  }
  // The codes of the eight pixels from column x.
  v8u codes8(int x) const { return codes8(centres(x)); }
  // The codes of eight pixels from their dzdx * (centre - fx0), the eight doubles at `slopes`
  // (the column part of the depth, the same for every row of a triangle: columnDepthParts).
  v8u codes8(const double* slopes) const {
    if constexpr (!kPlainFloat) {  // code()'s steps in two halves of four lanes
      v4d a, b;
      std::memcpy(&a, slopes, sizeof a);
      std::memcpy(&b, slopes + 4, sizeof b);
      return joined(codesOf((z0 + (a + rowPart)) + offset), codesOf((z0 + (b + rowPart)) + offset));
    } else {
#if defined(__AVX512F__)
      ClampLanes8 d;
      std::memcpy(&d, slopes, sizeof d);
      return floatCodes((z0 + (d + rowPart)) + offset);
#else
      v4d a, b;
      std::memcpy(&a, slopes, sizeof a);
      std::memcpy(&b, slopes + 4, sizeof b);
      return floatCodes((z0 + (a + rowPart)) + offset, (z0 + (b + rowPart)) + offset);
#endif
    }
  }
  uint32_t code(int x) const {
    double z = (z0 + (dzdx * ((double(x) + 0.5) - fx0) + rowPart)) + offset;
    if (!kPlainFloat && clamp) z = std::clamp(z, lo, hi);
    return codec.encode(z);
  }
};

// The row kind of a triangle (TriangleSetup::depthsInUnit says where the clamp can go).
RowKind rowKindOf(const TriangleSetup& t, const DepthCodec& codec, bool depthClamp) {
  if (!plainFloatDepths(codec, depthClamp)) return RowKind::Encoded;
  return t.depthsInUnit ? RowKind::UnitFloat : RowKind::PlainFloat;
}

// fn(std::true_type{}) or fn(std::false_type{}): a flag made a compile-time constant.
template <class Fn>
void withFlag(bool flag, Fn&& fn) {
  if (flag) fn(std::true_type{});
  else fn(std::false_type{});
}

// fn(kind) with the row kind as a compile-time constant.
template <class Fn>
void withKind(RowKind kind, Fn&& fn) {
  switch (kind) {
    case RowKind::Encoded: fn(std::integral_constant<RowKind, RowKind::Encoded>{}); return;
    case RowKind::PlainFloat: fn(std::integral_constant<RowKind, RowKind::PlainFloat>{}); return;
    case RowKind::UnitFloat: fn(std::integral_constant<RowKind, RowKind::UnitFloat>{}); return;
  }
}

// fn(compare, kind) with the depth function and the row kind as compile-time constants: what
// depthTestRows is instantiated for.
template <class Fn>
void withRowKind(CompareFunc func, RowKind kind, Fn&& fn) {
  withCompare(func, [&](auto f) { withKind(kind, [&](auto k) { fn(f, k); }); });
}
// The same with the depth-write flag as a third constant: fn(compare, kind, write).
template <class Fn>
void withRowKind(CompareFunc func, RowKind kind, bool write, Fn&& fn) {
  withRowKind(func, kind, [&](auto f, auto k) { withFlag(write, [&](auto w) { fn(f, k, w); }); });
}

}  // namespace

// The depth codes of n pixels of a row (RowDepth, of the triangle's row kind as the other span
// loops make them): eight at a time, then four, then one by one.
void FragmentProcessor::depthCodes(const TriangleSetup& t, int y, int x, int n, uint32_t* codes) const {
  auto fill = [&](auto kind) {
    const RowDepth<decltype(kind)::value> row(t, y, fb_.depthCodec(), state_.depthClamp, depthLo_, depthHi_);
    int i = 0;
    for (; i + 8 <= n; i += 8) {
      const v8u eight = row.codes8(x + i);
      std::memcpy(codes + i, &eight, sizeof eight);
    }
    if (i + 4 <= n) {
      const v4u four = row.codes4(x + i);
      std::memcpy(codes + i, &four, sizeof four);
      i += 4;
    }
    for (; i < n; ++i) codes[i] = row.code(x + i);
  };
  withKind(rowKindOf(t, fb_.depthCodec(), state_.depthClamp), fill);
}

void FragmentProcessor::processTriangle(const TriangleSetup& t, const Rect& region) {
  const bool watched = watch_ && watch_->observer && watch_->x >= t.minX && watch_->x <= t.maxX &&
                       watch_->y >= t.minY && watch_->y <= t.maxY;
  if (watched) return spanTriangle(t, region);  // queueSpan takes the watched pixel alone
  (this->*kernel_->kernel)(t, region);
}

void FragmentProcessor::spanTriangle(const TriangleSetup& t, const Rect& region) {
  rasterizeSpans(t, region, [&](int y, int xl, int xr, const int64_t* e) { queueSpan(t, y, xl, xr, e); });
  shadeWaiting();
}

namespace {

// The depth test of a vector of codes as a lane mask (all ones where it passes). Depth codes are
// below 2^31 (DepthCodec::encode: a float32 code of [0, 1] is at most 0x3f800000, a Unorm24 code
// below 2^24), so signed lanes order them as unsigned lanes do; x86 vectors compare signed lanes
// only, and an unsigned compare costs a sign flip on each side.
template <CompareFunc F, class Codes>
inline Codes codesPass(Codes incoming, Codes stored) {
  using Signed = std::conditional_t<sizeof(Codes) == sizeof(v8u), v8i, v4i>;
  return (Codes)passes<F>((Signed)incoming, (Signed)stored);
}

// pass ? a : b lane by lane, for a lane mask: one blend (the generic select first tests each lane
// against zero, not knowing the lanes are all ones or all zeros).
template <class Codes>
inline Codes selectLanes(Codes pass, Codes a, Codes b) {
#if defined(__AVX2__)
  if constexpr (sizeof(Codes) == sizeof(__m256i)) {
    using V = __m256i;
    return std::bit_cast<Codes>(_mm256_blendv_epi8(std::bit_cast<V>(b), std::bit_cast<V>(a), std::bit_cast<V>(pass)));
  }
#endif
#if defined(__SSE4_1__)
  if constexpr (sizeof(Codes) == sizeof(__m128i)) {
    using V = __m128i;
    return std::bit_cast<Codes>(_mm_blendv_epi8(std::bit_cast<V>(b), std::bit_cast<V>(a), std::bit_cast<V>(pass)));
  }
#endif
  return (a & pass) | (b & ~pass);
}

// The lanes of a step of eight pixels starting at column `first` whose columns are in [lo, hi], as
// a lane mask: the live lanes.
inline v8u liveLanes(int first, int lo, int hi) {
  const v8i column = first + v8i{0, 1, 2, 3, 4, 5, 6, 7};
  return (v8u)((column >= lo) & (column <= hi));
}

// One step of depthTestRows: the eight pixels of a row from column x (stored: the row's depth
// codes), `live` the lanes to test; returns the lanes that pass. Whole: every lane live. Without a
// depth test a step with dead lanes still reads the depths (block may store them back), where the
// framebuffer has a depth buffer at all.
template <CompareFunc F, bool Whole, class Block>
inline v8u depthStep(const uint32_t* stored, bool hasDepth, size_t rowStart, int x, v8u codes, v8u live,
                     const Block& block) {
  v8u before{};
  if constexpr (F != CompareFunc::Always) std::memcpy(&before, stored + x, sizeof before);
  else if (!Whole && hasDepth) std::memcpy(&before, stored + x, sizeof before);
  const v8u pass = codesPass<F>(codes, before) & live;
  block(rowStart + size_t(x), codes, before, live, pass);
  return pass;
}

// Triangles of at least this many rows in a band (and 17 columns) take the column part of their
// depths from a table made once per triangle and band (columnDepthParts).
constexpr int kSlopeRows = 8;

// The column part of a depth, dzdx * (centre - fx0), for every column a step of the
// triangle's rows in the region can start at or cover — the same operations as RowDepth's, so the
// same bits — indexed by column; nullptr where the triangle has too few rows or columns for the
// table to pay. A row then adds three numbers a pixel instead of four and a multiplication (the
// map pass and the volume sides are bound by their double additions). The table is made in
// `table` (SpanScratch::columnDepthParts, only grown), valid until its next use.
const double* columnDepthParts(const TriangleSetup& t, const Rect& region, int bufferWidth, std::vector<double>& table) {
  const int y0 = std::max(t.minY, region.y), y1 = std::min(t.maxY, region.y + region.height - 1);
  if (y1 - y0 + 1 < kSlopeRows || bufferWidth < 8) return nullptr;
  // A band that cuts the triangle: only the columns it covers in these rows. A shadow volume's
  // side reaches across the screen, and a band of rows holds a stretch of it.
  const bool cut = y0 > t.minY || y1 < t.maxY;
  const ColumnRange columns = cut ? columnsInRows(t, region, y0, y1)
                                  : ColumnRange{std::max(t.minX, region.x), std::min(t.maxX, region.x + region.width - 1)};
  const int x0 = columns.first, x1 = columns.last;
  if (x1 - x0 < 16) return nullptr;
  const int from = x0 - 7;  // a row's last step starts at most seven columns left of x0
  const size_t entries = size_t(x1 + 8 - from);
  if (table.size() < entries) table.resize(entries);  // only grown: resizing down and up again zeroes
  // Four entries a step (GCC left the loop scalar); the centres stepped by 4.0 are exact, and
  // each lane's subtraction and multiplication are the scalar ones.
  double* const out = table.data();
  const double dzdx = t.dzdx, fx0 = t.v[0].fx;
  v4d centres = double(from) + v4d{0.5, 1.5, 2.5, 3.5};
  size_t c = 0;
  for (; c + 4 <= entries; c += 4, centres += 4.0) {
    const v4d parts = dzdx * (centres - fx0);
    std::memcpy(out + c, &parts, sizeof parts);
  }
  for (; c < entries; ++c) out[c] = dzdx * ((double(from + int(c)) + 0.5) - fx0);
  return out - from;
}

// The rows of a triangle, depth tested eight pixels per step: block(at, codes, stored, live, pass)
// for each eight pixels from buffer index `at` (v8u vectors of codes; `live` the lanes inside the
// span and `pass` the live lanes that pass, lane masks). What is left of a span after its whole
// steps of eight — a short span all of it — is one more step, over the eight pixels of the row
// from the first one left, or the row's last eight where the row ends sooner: one step without
// branches in place of up to seven single pixels. Its other lanes are dead; block may store them
// back as they were read (they are pixels of the same row, which this thread owns). Narrow
// triangles go a row at a time in one such window (rasterizeNarrowRows). A framebuffer narrower
// than eight pixels has no such window; its rows go pixel by pixel, single(at, code, pass).
// Counts the fragments and the failed depth tests. F = Always (no depth test) reads no depth but
// the dead lanes', and none without a depth buffer (where block writes no depth).
template <CompareFunc F, RowKind K, class Block, class Single>
void depthTestRows(const TriangleSetup& t, const Rect& region, const Framebuffer& fb, bool clamp, double lo, double hi,
                   std::vector<double>& columnTable, uint64_t& fragments, uint64_t& failed, const Block& block,
                   const Single& single) {
  const uint32_t* const depth = fb.depthCodes().data();
  const bool hasDepth = fb.hasDepth();
  const int width = fb.width();
  uint64_t rowsFragments = 0, rowsPassed = 0;  // locals: the loops keep them in registers
  v8u passed8{};  // passed tests per lane, summed once per triangle rather than per row
  if (isNarrow(t, region, width)) {
    v8u covered8{};  // covered pixels per lane
    rasterizeNarrowRows(t, region, width, [&, depth, hasDepth, width](int y, int window, NarrowLanes covered) {
      const size_t rowStart = size_t(y) * size_t(width);
      const RowDepth<K> row(t, y, fb.depthCodec(), clamp, lo, hi);
      const Block rowBlock = block;  // a copy, as in the span rows below
      const v8u live = (v8u)covered;
      // No row of a depth buffer that does not exist: offsetting its null pointer is undefined.
      const uint32_t* const stored = hasDepth ? depth + rowStart : nullptr;
      passed8 -= depthStep<F, false>(stored, hasDepth, rowStart, window, row.codes8(window), live, rowBlock);
      covered8 -= live;
    });
    for (int lane = 0; lane < 8; ++lane) rowsFragments += uint64_t(covered8[lane]);
  } else {
    const double* slopes = columnDepthParts(t, region, width, columnTable);
    // Inlined into the row walk: GCC called it once a row, saving and restoring six registers and
    // reloading the closure each time — a cost paid per row of every span.
    auto spanRow = [&, depth, hasDepth, width, slopes](int y, int xl, int xr) __attribute__((always_inline)) {
      const size_t rowStart = size_t(y) * size_t(width);
      const RowDepth<K> row(t, y, fb.depthCodec(), clamp, lo, hi);
      // Copies for the row: stores through the buffers may alias anything in memory, so values
      // read through the closures would be read again after every store.
      const uint32_t* const stored = hasDepth ? depth + rowStart : nullptr;  // (null: no buffer, no row)
      const double* const rowSlopes = slopes;  // (the map pass read it from the closure every step)
      const Block rowBlock = block;
      const Single rowSingle = single;
      v8u rowPassed8{};  // in a register through the row (a passing lane is -1); the triangle's in memory
      int x = xl;
      if (rowSlopes) {
        for (; x + 8 <= xr + 1; x += 8)
          rowPassed8 -= depthStep<F, true>(stored, hasDepth, rowStart, x, row.codes8(rowSlopes + x), ~v8u{}, rowBlock);
      } else {
        for (auto centres = row.centres(x); x + 8 <= xr + 1; x += 8, centres = row.nextStep(centres))
          rowPassed8 -= depthStep<F, true>(stored, hasDepth, rowStart, x, row.codes8(centres), ~v8u{}, rowBlock);
      }
      if (x <= xr && width >= 8) {
        const int first = std::min(x, width - 8);
        const v8u codes = rowSlopes ? row.codes8(rowSlopes + first) : row.codes8(first);
        rowPassed8 -= depthStep<F, false>(stored, hasDepth, rowStart, first, codes, liveLanes(first, x, xr), rowBlock);
      } else {
        for (; x <= xr; ++x) {
          const uint32_t code = row.code(x);
          const bool pass = passes<F>(code, F == CompareFunc::Always ? code : stored[x]);
          rowsPassed += pass;
          rowSingle(rowStart + size_t(x), code, pass);
        }
      }
      passed8 += rowPassed8;
      rowsFragments += uint64_t(xr - xl + 1);
    };
    rasterizeRowSpans(t, region, spanRow);
  }
  for (int lane = 0; lane < 8; ++lane) rowsPassed += uint64_t(passed8[lane]);
  fragments += rowsFragments;
  failed += rowsFragments - rowsPassed;
}

}  // namespace

// Shadow-volume counting for a whole triangle: the stencil test always passes, so each fragment
// adds the byte of its outcome (depth pass or fail) for its facing, modulo 256 — rows straight from
// the rasterizer, eight pixels per step, the depth function and the two deltas fixed per triangle.
void FragmentProcessor::countTriangle(const TriangleSetup& t, const Rect& region) {
  const StencilFaceState& face = state_.stencil[t.facing];
  uint8_t onPass = 0, onFail = 0;
  wrapDelta(face.dppass, onPass);
  wrapDelta(face.dpfail, onFail);
  uint8_t* const stencil = countTarget_ ? countTarget_ : fb_.stencil().data();
  uint64_t fragments = 0, failed = 0;
  // The deltas in every lane, made once: the stencil stores are byte stores, which may alias
  // anything, so a delta read from a byte would be read and broadcast again at every step.
  const v8u passDelta = v8u{} + onPass, failDelta = v8u{} + onFail;
  withRowKind(usesDepth_ ? state_.depthFunc : CompareFunc::Always, rowKindOf(t, fb_.depthCodec(), state_.depthClamp),
              [&](auto f, auto kind) {
    depthTestRows<decltype(f)::value, decltype(kind)::value>(
        t, region, fb_, state_.depthClamp, depthLo_, depthHi_, scratch_.columnDepthParts, fragments, failed,
        [stencil, passDelta, failDelta](size_t at, v8u, v8u, v8u live, v8u pass) {
          v8b bytes;
          std::memcpy(&bytes, stencil + at, sizeof bytes);
          bytes += lowBytes(selectLanes(pass, passDelta, failDelta) & live);  // a dead lane adds 0
          std::memcpy(stencil + at, &bytes, sizeof bytes);
        },
        [stencil, onPass, onFail](size_t at, uint32_t, bool pass) {
          stencil[at] = uint8_t(stencil[at] + (pass ? onPass : onFail));
        });
  });
  stats_.fragments += fragments;
  stats_.depthFailed += failed;
  stats_.stencilWrites += (onPass != 0 ? fragments - failed : 0) + (onFail != 0 ? failed : 0);
}

// Depth (and nothing else) for a whole triangle: the shadow maps' pass, eight pixels per step. The
// store is unconditional (the old value where the test fails); the pixels are this thread's.
void FragmentProcessor::depthTriangle(const TriangleSetup& t, const Rect& region) {
  uint32_t* const depth = fb_.depthCodes().data();
  uint64_t fragments = 0, failed = 0;
  auto rows = [&](auto f, auto kind, auto write) {
    depthTestRows<decltype(f)::value, decltype(kind)::value>(
        t, region, fb_, state_.depthClamp, depthLo_, depthHi_, scratch_.columnDepthParts, fragments, failed,
        [depth](size_t at, v8u codes, v8u stored, v8u, v8u pass) {
          if constexpr (decltype(write)::value) {
            const v8u next = selectLanes(pass, codes, stored);
            std::memcpy(depth + at, &next, sizeof next);
          }
        },
        [depth](size_t at, uint32_t code, bool pass) {
          if (decltype(write)::value && pass) depth[at] = code;
        });
  };
  withRowKind(usesDepth_ ? state_.depthFunc : CompareFunc::Always, rowKindOf(t, fb_.depthCodec(), state_.depthClamp),
              writesDepth_, rows);
  stats_.fragments += fragments;
  stats_.depthFailed += failed;
}

// One colour for every fragment that passes the depth test, and its depth when written: the
// ambient pass of the shadow volumes (no stencil, no blending, every channel), eight pixels per
// step. The colour is the one writeColors stores for a constant colour.
void FragmentProcessor::constantColorTriangle(const TriangleSetup& t, const Rect& region) {
  uint32_t* const depth = usesDepth_ ? fb_.depthCodes().data() : nullptr;
  glm::vec4* const color = fb_.color().data();
  const glm::vec4 value = writeColor(glm::vec4(0.0f), *constantColor_, state_.colorMask);
  uint64_t fragments = 0, failed = 0;
  auto rows = [&](auto f, auto kind, auto write) {
    constexpr bool kWrite = decltype(write)::value;
    depthTestRows<decltype(f)::value, decltype(kind)::value>(
        t, region, fb_, state_.depthClamp, depthLo_, depthHi_, scratch_.columnDepthParts, fragments, failed,
        [depth, color, value](size_t at, v8u codes, v8u stored, v8u, v8u pass) {
          if constexpr (kWrite) {
            const v8u next = selectLanes(pass, codes, stored);
            std::memcpy(depth + at, &next, sizeof next);
          }
          for (int lane = 0; lane < 8; ++lane)
            if (pass[lane]) color[at + size_t(lane)] = value;
        },
        [depth, color, value](size_t at, uint32_t code, bool pass) {
          if (!pass) return;
          if constexpr (kWrite) depth[at] = code;
          color[at] = value;
        });
  };
  withRowKind(usesDepth_ ? state_.depthFunc : CompareFunc::Always, rowKindOf(t, fb_.depthCodec(), state_.depthClamp),
              writesDepth_, rows);
  stats_.fragments += fragments;
  stats_.depthFailed += failed;
  stats_.colorWrites += fragments - failed;
}

namespace {

// The perspective weights of a chunk's survivors, b_i = E_i / w_i at each (interpolateVaryings'
// arithmetic: the same bits). The weights need double(E) of the exact integer edge values. Where
// every value in the chunk is below 2^52 in magnitude, E = E_start + stepX * i is exact in double
// arithmetic, which vectorises; otherwise it is formed in 64-bit integers first.
void chunkWeights(const TriangleSetup& t, const int64_t e[3], int x, int xl, int n, const int* survivors, int survived,
                  double* b0, double* b1, double* b2) {
  int64_t start[3];
  bool smallValues = true;
  for (int j = 0; j < 3; ++j) {
    start[j] = e[j] + t.stepX[j] * (x - xl);
    const int64_t end = start[j] + t.stepX[j] * (n - 1), limit = int64_t(1) << 52;
    smallValues = smallValues && start[j] > -limit && start[j] < limit && end > -limit && end < limit;
  }
  if (smallValues) {
    const double e0 = double(start[0]), e1 = double(start[1]), e2 = double(start[2]);
    const double s0 = double(t.stepX[0]), s1 = double(t.stepX[1]), s2 = double(t.stepX[2]);
    const double w0 = t.v[0].invW, w1 = t.v[1].invW, w2 = t.v[2].invW;
    for (int k = 0; k < survived; ++k) {
      const double i = double(survivors[k]);
      b0[k] = (e0 + s0 * i) * w0;
      b1[k] = (e1 + s1 * i) * w1;
      b2[k] = (e2 + s2 * i) * w2;
    }
  } else {
    for (int k = 0; k < survived; ++k) {
      const int64_t i = survivors[k];
      b0[k] = double(start[0] + t.stepX[0] * i) * t.v[0].invW;
      b1[k] = double(start[1] + t.stepX[1] * i) * t.v[1].invW;
      b2[k] = double(start[2] + t.stepX[2] * i) * t.v[2].invW;
    }
  }
}

// Chunks with at least this many survivors are shaded at once; fewer wait for the triangle's next
// ones (FragmentProcessor::Waiting). Copying a chunk this full into the waiting batch would
// cost a copy per fragment and gain nothing.
constexpr int kShadeAtOnce = 32;

}  // namespace

// processFragment for a chunk: every test and write per fragment in GL order; the fragments
// that reach colour are shaded together and written by writeColors — at once where the chunk has
// many, otherwise after they have waited for the triangle's next ones (shadeWaiting).
void FragmentProcessor::generalChunk(const TriangleSetup& t, int y, int x, int n, const uint32_t* codes, int xl,
                                     const int64_t e[3]) {
  const size_t at = fb_.index(x, y);
  int survivors[kChunk];
  const int survived = testChunk(t, at, n, codes, survivors);
  if (survived == 0 || !writesColor_) return;
  stats_.colorWrites += uint64_t(survived);
  glm::vec4* color = fb_.color().data() + at;
  if (constantColor_) {
    writeColors(color, survivors, survived, nullptr);
    return;
  }
  // Blending reads the colour buffer, which is far larger than the caches: ask for the survivors'
  // lines now, and shading hides the wait for them.
  if (state_.blend.enabled) {
    const char* first = reinterpret_cast<const char*>(color + survivors[0]);
    const char* last = reinterpret_cast<const char*>(color + survivors[survived - 1] + 1);
    for (const char* line = first; line < last; line += 64) __builtin_prefetch(line, 1);
  }
  // The survivors' pixels, depths and weights, from entry `from` of f on.
  auto add = [&](Shading& f, int from) {
    for (int k = 0; k < survived; ++k) {
      f.x[from + k] = x + survivors[k];
      f.y[from + k] = y;
      f.depth[from + k] = fb_.depthCodec().decode(codes[survivors[k]]);
    }
    chunkWeights(t, e, x, xl, n, survivors, survived, f.b0 + from, f.b1 + from, f.b2 + from);
    f.count = from + survived;
  };
  if (survived >= kShadeAtOnce) {
    Shading now;
    add(now, 0);
    shadeAndWrite(t, now, color, survivors);
    return;
  }
  if (waiting_.count + survived > kMaxBatch) shadeWaiting();
  Waiting& w = waiting_;
  w.triangle = &t;
  for (int k = 0; k < survived; ++k) w.at[w.count + k] = at + size_t(survivors[k]);
  add(w, w.count);
}

void FragmentProcessor::shadeWaiting() {
  if (waiting_.count == 0) return;
  shadeAndWrite(*waiting_.triangle, waiting_, fb_.color().data(), waiting_.at);
  waiting_.count = 0;
}

// Varyings at each fragment, column by column (interpolateVaryings' arithmetic), then one call to
// the shader for all of them, then the writes: fragment k's colour goes to color[offsets[k]].
template <class Offset>
void FragmentProcessor::shadeAndWrite(const TriangleSetup& t, const Shading& f, glm::vec4* color, const Offset* offsets) {
  const int count = f.count;
  double inv[kMaxBatch];
  double varyings[kMaxVaryings][kMaxBatch];
  for (int k = 0; k < count; ++k) inv[k] = 1.0 / (f.b0[k] + f.b1[k] + f.b2[k]);
  FragmentBatch batch;
  batch.count = count;
  batch.facing = t.facing;
  batch.x = f.x;
  batch.y = f.y;
  batch.depth = f.depth;
  for (int i = 0; i < 3; ++i) batch.triangle[i] = t.v[i].source;
  for (int j = 0; j < varyingCount_; ++j) {
    const double a0 = t.v[0].source->varyings[size_t(j)], a1 = t.v[1].source->varyings[size_t(j)],
                 a2 = t.v[2].source->varyings[size_t(j)];
    double* out = varyings[j];
    for (int k = 0; k < count; ++k) out[k] = (f.b0[k] * a0 + f.b1[k] * a1 + f.b2[k] * a2) * inv[k];
    batch.varyings[j] = out;
  }
  glm::dvec4 shaded[kMaxBatch];
  shader_->shadeBatch(batch, shaded);
  writeColors(color, offsets, count, shaded);
}

namespace {

// The lanes set in a mask (all ones or all zeros per lane) as four bits.
inline unsigned laneBits(v4u mask) {
#if defined(__SSE2__)
  __m128 m;
  std::memcpy(&m, &mask, sizeof m);
  return unsigned(_mm_movemask_ps(m));
#else
  return (mask[0] & 1u) | (mask[1] & 2u) | (mask[2] & 4u) | (mask[3] & 8u);
#endif
}

// For each 4-bit mask, the lanes whose bits are set, in order (the rest 0).
constexpr std::array<std::array<int, 4>, 16> kSetLanes = [] {
  std::array<std::array<int, 4>, 16> table{};
  for (unsigned m = 0; m < 16; ++m) {
    int k = 0;
    for (int lane = 0; lane < 4; ++lane)
      if (m & (1u << lane)) table[m][size_t(k++)] = lane;
  }
  return table;
}();

// Appends first + lane for each set lane of `mask` to survivors[count...]; returns the new count.
// Writes four entries whatever the mask: the caller's array has them (count <= first, and
// first + 4 <= its size).
inline int appendLanes(v4u mask, int first, int* survivors, int count) {
  const unsigned bits = laneBits(mask);
  v4i lanes;
  std::memcpy(&lanes, kSetLanes[bits].data(), sizeof lanes);
  lanes += first;
  std::memcpy(survivors + count, &lanes, sizeof lanes);
  return count + std::popcount(bits);
}

}  // namespace

// testChunk for the states of the colour passes, where no stencil value can change (stencil
// unused, or every op KEEP, or a zero write mask) and the functions are the usual ones: the tests
// as lane masks, four pixels per step. Returns -1 for any other state.
int FragmentProcessor::filterChunk(const StencilFaceState& sface, size_t at, int n, const uint32_t* codes,
                                   int* survivors) {
  const bool stencilWrites = usesStencil_ && stencilFaceMayWrite(sface);
  const CompareFunc stencilFunc = usesStencil_ ? sface.func : CompareFunc::Always;
  const CompareFunc depthFunc = usesDepth_ ? state_.depthFunc : CompareFunc::Always;
  auto usual = [](CompareFunc f, CompareFunc a, CompareFunc b) { return f == CompareFunc::Always || f == a || f == b; };
  if (stencilWrites || !usual(stencilFunc, CompareFunc::Equal, CompareFunc::NotEqual) ||
      !usual(depthFunc, CompareFunc::Less, CompareFunc::LEqual))
    return -1;
  const uint8_t* stencil = usesStencil_ ? fb_.stencil().data() + at : nullptr;
  uint32_t* depth = usesDepth_ ? fb_.depthCodes().data() + at : nullptr;
  const uint32_t ref = maskedStencilReference(sface), mask = sface.mask;
  int survived = 0;
  uint64_t stencilFailed = 0, depthFailed = 0;
  auto run = [&](auto sf, auto df) {
    constexpr CompareFunc SF = decltype(sf)::value, DF = decltype(df)::value;
    int i = 0;
    v4u stencilFails{}, depthFails{};  // per lane, summed after the loop
    for (; i + 4 <= n; i += 4) {
      v4u sPass = v4u{} - 1, dPass = v4u{} - 1;
      if constexpr (SF != CompareFunc::Always) {
        v4b bytes;
        std::memcpy(&bytes, stencil + i, sizeof bytes);
        sPass = passes<SF>(v4u{} + ref, __builtin_convertvector(bytes, v4u) & mask);
      }
      v4u code, stored{};
      std::memcpy(&code, codes + i, sizeof code);
      if constexpr (DF != CompareFunc::Always) {
        std::memcpy(&stored, depth + i, sizeof stored);
        dPass = passes<DF>(code, stored);
      }
      const v4u both = sPass & dPass;
      if (writesDepth_) {
        const v4u next = both ? code : stored;
        std::memcpy(depth + i, &next, sizeof next);
      }
      stencilFails += ~sPass & 1u;
      depthFails += sPass & ~dPass & 1u;
      survived = appendLanes(both, i, survivors, survived);
    }
    for (int lane = 0; lane < 4; ++lane) {
      stencilFailed += stencilFails[lane];
      depthFailed += depthFails[lane];
    }
    for (; i < n; ++i) {
      if (!passes<SF>(ref, uint32_t(SF == CompareFunc::Always ? 0 : stencil[i]) & mask)) {
        ++stencilFailed;
        continue;
      }
      if (!passes<DF>(codes[i], DF == CompareFunc::Always ? 0 : depth[i])) {
        ++depthFailed;
        continue;
      }
      if (writesDepth_) depth[i] = codes[i];
      survivors[survived++] = i;
    }
  };
  auto withDepth = [&](auto sf) {
    switch (depthFunc) {
      case CompareFunc::Less: run(sf, std::integral_constant<CompareFunc, CompareFunc::Less>{}); break;
      case CompareFunc::LEqual: run(sf, std::integral_constant<CompareFunc, CompareFunc::LEqual>{}); break;
      default: run(sf, std::integral_constant<CompareFunc, CompareFunc::Always>{}); break;
    }
  };
  switch (stencilFunc) {
    case CompareFunc::Equal: withDepth(std::integral_constant<CompareFunc, CompareFunc::Equal>{}); break;
    case CompareFunc::NotEqual: withDepth(std::integral_constant<CompareFunc, CompareFunc::NotEqual>{}); break;
    default: withDepth(std::integral_constant<CompareFunc, CompareFunc::Always>{}); break;
  }
  stats_.stencilFailed += stencilFailed;
  stats_.depthFailed += depthFailed;
  return survived;
}

// Stencil test, depth test, stencil update and depth write for a chunk, as processFragment does them;
// returns how many fragments passed both tests and lists them in `survivors`.
int FragmentProcessor::testChunk(const TriangleSetup& t, size_t at, int n, const uint32_t* codes, int* survivors) {
  const StencilFaceState& sface = state_.stencil[t.facing];
  if (const int survived = filterChunk(sface, at, n, codes, survivors); survived >= 0) return survived;
  uint8_t* stencil = usesStencil_ ? fb_.stencil().data() + at : nullptr;
  uint32_t* depth = usesDepth_ ? fb_.depthCodes().data() + at : nullptr;
  int survived = 0;
  uint64_t stencilFailed = 0, depthFailed = 0, stencilWrites = 0;
  auto updateStencil = [&](int i, StencilOp op) {
    const uint8_t next = writeStencil(stencil[i], applyStencilOp(op, stencil[i], sface.ref), sface.writeMask);
    stencilWrites += next != stencil[i];
    stencil[i] = next;
  };
  withCompare(depth ? state_.depthFunc : CompareFunc::Always, [&](auto f) {
    for (int i = 0; i < n; ++i) {
      if (stencil && !stencilTest(sface, stencil[i])) {
        ++stencilFailed;
        updateStencil(i, sface.sfail);
        continue;
      }
      const bool depthPassed = passes<decltype(f)::value>(codes[i], depth ? depth[i] : 0);
      if (stencil) updateStencil(i, depthPassed ? sface.dppass : sface.dpfail);
      if (!depthPassed) {
        ++depthFailed;
        continue;
      }
      if (writesDepth_) depth[i] = codes[i];
      survivors[survived++] = i;
    }
  });
  stats_.stencilFailed += stencilFailed;
  stats_.depthFailed += depthFailed;
  stats_.stencilWrites += stencilWrites;
  return survived;
}

// blend() and writeColor() for each fragment k, at color[offsets[k]]; `shaded` is nullptr for a
// constant colour. The two cases every frame has — no blending with all channels written, and
// ONE/ONE (the lit passes' sum) — skip the general blend's per-channel factor switches (x * 1.0
// is x exactly, and 0 * x + s is s, so they give the same bits).
template <class Offset>
void FragmentProcessor::writeColors(glm::vec4* color, const Offset* offsets, int count, const glm::dvec4* shaded) const {
  const BlendState& b = state_.blend;
  const bool allChannels = state_.colorMask[0] && state_.colorMask[1] && state_.colorMask[2] && state_.colorMask[3];
  auto source = [&](int k) -> const glm::dvec4& { return shaded ? shaded[k] : *constantColor_; };
  static_assert(sizeof(glm::dvec4) == sizeof(v4d) && sizeof(glm::vec4) == sizeof(v4f));
  auto clamped = [](v4d c) { return clampUnit(c); };
  auto load = [](const glm::dvec4& c) {
    v4d v;
    std::memcpy(&v, &c, sizeof v);
    return v;
  };
  auto store = [](glm::vec4& dst, v4d c) {
    const v4f f = __builtin_convertvector(c, v4f);
    std::memcpy(&dst, &f, sizeof f);
  };
  if (allChannels && !b.enabled) {
    if (!shaded) {
      const glm::vec4 value = writeColor(glm::vec4(0.0f), *constantColor_, state_.colorMask);
      for (int k = 0; k < count; ++k) color[offsets[k]] = value;
      return;
    }
    for (int k = 0; k < count; ++k) store(color[offsets[k]], clamped(load(shaded[k])));
    return;
  }
  if (allChannels && b.enabled && b.src == BlendFactor::One && b.dst == BlendFactor::One) {
    for (int k = 0; k < count; ++k) {
      glm::vec4& dst = color[offsets[k]];
      v4f stored;
      std::memcpy(&stored, &dst, sizeof stored);
      store(dst, clamped(clamped(load(source(k))) + __builtin_convertvector(stored, v4d)));
    }
    return;
  }
  for (int k = 0; k < count; ++k) {
    glm::vec4& dst = color[offsets[k]];
    dst = writeColor(dst, blend(b, source(k), glm::dvec4(dst)), state_.colorMask);
  }
}

}  // namespace shadowref
