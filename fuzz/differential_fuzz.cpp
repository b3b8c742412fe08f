// libFuzzer target: the input is a command stream, rendered by the reference pipeline and by the
// fast executor at one and at three threads; every byte of every buffer, every statistics counter
// and every pixel-history event must agree. The first difference stops the run with the command,
// the buffer and the pixel where it appeared.
//
// The bytes decode as commands, one opcode byte each: draw (state and one to four triangles from
// the following bytes), clear (buffers, values, scissor and masks), glAccum, end of pass, watch a
// pixel. Coordinates come from a small table of values that includes the extremes the pipeline
// must handle (w = 0, w < 0, far outside the guard band, exactly on a pixel centre), so the
// fuzzer spends its time on state and geometry combinations, not on finding numbers.
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include "gl/pipeline.h"

namespace {

using namespace shadowref;

constexpr int kWidth = 23, kHeight = 17;

// Reads the input a byte at a time; past its end every read is 0.
class Bytes {
 public:
  Bytes(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  bool done() const { return at_ >= size_; }
  uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  bool flag() { return byte() & 1; }
  template <class E>
  E pick(int count) { return E(byte() % count); }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t at_ = 0;
};

// Clip-space coordinates: ordinary values, values on and across the clip planes, and extremes.
double coordinate(Bytes& in) {
  static constexpr double kTable[] = {0.0, 0.5, -0.5, 1.0, -1.0, 0.25, -0.75, 0.999, 1.001, 2.0, -2.0,
                                      1e-9, -1e-9, 3e5, -3e5, 1e12, 0.125, 0.3, -0.3, 0.7};
  const uint8_t b = in.byte();
  if (b < 200) return (double(b) - 100.0) / 64.0;  // a grid finer than a pixel, inside and out
  return kTable[b % (sizeof(kTable) / sizeof(kTable[0]))];
}

double wCoordinate(Bytes& in) {
  static constexpr double kTable[] = {1.0, 1.0, 1.0, 0.5, 2.0, 0.0, -1.0, 1e-8, 1e6, 0.75};
  return kTable[in.byte() % 10];
}

ClipVertex vertex(Bytes& in) {
  ClipVertex v;
  v.position = {coordinate(in), coordinate(in), coordinate(in), wCoordinate(in)};
  for (int i = 0; i < 8; ++i) v.varyings[size_t(i)] = double(in.byte()) / 255.0;
  return v;
}

StencilFaceState stencilFace(Bytes& in) {
  StencilFaceState s;
  s.func = in.pick<CompareFunc>(8);
  s.ref = int(in.byte()) - 8;  // below 0 and above 255 are clamped when used
  s.mask = in.flag() ? 0xFF : in.byte();
  s.writeMask = in.flag() ? 0xFF : in.byte();
  s.sfail = in.pick<StencilOp>(8);
  s.dpfail = in.pick<StencilOp>(8);
  s.dppass = in.pick<StencilOp>(8);
  return s;
}

RenderState state(Bytes& in) {
  RenderState s;
  s.viewport = {int(in.byte() % 5) - 2, int(in.byte() % 5) - 2, kWidth - int(in.byte() % 7) + 3,
                kHeight - int(in.byte() % 7) + 3, in.flag() ? 0.0 : 0.25, in.flag() ? 1.0 : 0.8};
  s.scissorTest = in.byte() % 4 == 0;
  s.scissor = {int(in.byte() % kWidth), int(in.byte() % kHeight), int(in.byte() % 30), int(in.byte() % 30)};
  s.cull = in.pick<CullMode>(4);
  s.frontFace = in.pick<FrontFace>(2);
  s.depthTest = in.flag();
  s.depthFunc = in.pick<CompareFunc>(8);
  s.depthWrite = in.flag();
  s.depthClamp = in.byte() % 4 == 0;
  s.clipFar = in.byte() % 4 != 0;
  s.polygonOffset = {in.byte() % 4 == 0, double(int(in.byte() % 9) - 4), double(int(in.byte() % 9) - 4)};
  s.stencilTest = in.flag();
  s.stencil[FrontFacing] = stencilFace(in);
  s.stencil[BackFacing] = in.flag() ? s.stencil[FrontFacing] : stencilFace(in);
  s.blend = {in.flag(), in.pick<BlendFactor>(10), in.pick<BlendFactor>(10)};
  for (bool& m : s.colorMask) m = in.byte() % 5 != 0;
  return s;
}

struct Shaders {
  ColorVaryingShader varying;
  ConstantColorShader constant{{0.25, 0.5, 1.0, 0.5}};
  const FragmentShader* pick(Bytes& in) const {
    switch (in.byte() % 3) {
      case 0: return nullptr;
      case 1: return &varying;
      default: return &constant;
    }
  }
};

// One draw's arrays, kept until the end of its pass (the draw contract).
struct KeptDraw {
  RenderState state;
  std::vector<ClipVertex> vertices;
  std::vector<uint32_t> indices;
};

[[noreturn]] void differ(size_t command, const char* what, size_t index) {
  std::fprintf(stderr, "differential: after command %zu the %s differs first at %zu\n", command, what, index);
  std::abort();
}

template <class Vector>
void compareBuffer(const Vector& a, const Vector& b, size_t command, const char* what) {
  if (a.size() != b.size()) differ(command, what, size_t(-1));
  const size_t bytes = a.size() * sizeof(a[0]);
  if (bytes == 0 || std::memcmp(a.data(), b.data(), bytes) == 0) return;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::memcmp(&a[i], &b[i], sizeof(a[i])) != 0) differ(command, what, i);
}

class Recorder final : public FragmentObserver {
 public:
  // Field by field: the struct's padding bytes are not part of the event.
  void onFragment(const FragmentEvent& e) override {
    add(e.x), add(e.y), add(e.drawIndex), add(e.drawTag), add(e.facing), add(e.depth), add(e.storedDepth);
    add(e.scissorPassed), add(e.stencilPassed), add(e.depthPassed), add(e.stencilBefore), add(e.stencilAfter);
    add(e.colorBefore), add(e.colorAfter);
  }
  std::vector<uint8_t> bytes;

 private:
  template <class T>
  void add(const T& value) {
    const auto* p = reinterpret_cast<const uint8_t*>(&value);
    bytes.insert(bytes.end(), p, p + sizeof(value));
  }
};

struct Run {
  explicit Run(PipelineKind kind, int threads, DepthFormat format)
      : fb(kWidth, kHeight, format), pipeline(makePipeline(kind, fb, threads)) {}
  Framebuffer fb;
  std::unique_ptr<Pipeline> pipeline;
  Recorder recorder;
};

void compare(std::array<std::unique_ptr<Run>, 3>& runs, size_t command) {
  Framebuffer& ref = runs[0]->pipeline->framebuffer();
  for (size_t r = 1; r < runs.size(); ++r) {
    Framebuffer& fast = runs[r]->pipeline->framebuffer();
    compareBuffer(ref.color(), fast.color(), command, "colour buffer");
    compareBuffer(ref.depthCodes(), fast.depthCodes(), command, "depth buffer");
    compareBuffer(ref.stencil(), fast.stencil(), command, "stencil buffer");
    compareBuffer(ref.accum(), fast.accum(), command, "accumulation buffer");
    const RasterStats& a = runs[0]->pipeline->stats();
    const RasterStats& b = runs[r]->pipeline->stats();
    if (std::memcmp(&a, &b, sizeof(a)) != 0) differ(command, "statistics", 0);
    compareBuffer(runs[0]->recorder.bytes, runs[r]->recorder.bytes, command, "pixel history");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Bytes in(data, size);
  const DepthFormat format = in.flag() ? DepthFormat::Unorm24 : DepthFormat::Float32;
  std::array<std::unique_ptr<Run>, 3> runs{std::make_unique<Run>(PipelineKind::Reference, 1, format),
                                           std::make_unique<Run>(PipelineKind::Fast, 1, format),
                                           std::make_unique<Run>(PipelineKind::Fast, 3, format)};
  const Shaders shaders;
  std::vector<std::unique_ptr<KeptDraw>> pass;
  auto endPass = [&] {
    for (auto& run : runs) run->pipeline->endPass();
    pass.clear();
  };
  for (size_t command = 0; command < 64 && !in.done(); ++command) {
    switch (in.byte() % 8) {
      case 0: case 1: case 2: case 3: {  // a draw
        auto draw = std::make_unique<KeptDraw>();
        draw->state = state(in);
        const int triangles = 1 + in.byte() % 4;
        const bool indexed = in.flag();
        for (int v = 0; v < 3 * triangles; ++v) draw->vertices.push_back(vertex(in));
        if (indexed)
          for (int v = 0; v < 3 * triangles; ++v) draw->indices.push_back(uint32_t(in.byte() % (3 * triangles)));
        const DrawCall call{.state = &draw->state, .vertices = draw->vertices, .indices = draw->indices,
                            .shader = shaders.pick(in), .tag = uint32_t(command)};
        for (auto& run : runs) run->pipeline->draw(call);
        pass.push_back(std::move(draw));
        break;
      }
      case 4: {  // a clear, in its place among the pass's draws
        ClearRequest request{.state = state(in)};
        if (in.flag()) request.color = glm::vec4(in.byte() / 255.0f, in.byte() / 255.0f, 0.5f, 1.0f);
        if (in.flag()) request.depth = double(in.byte()) / 255.0;
        if (in.flag()) request.stencil = int(in.byte()) - 8;
        if (in.byte() % 4 == 0) request.accum = glm::vec4(-0.5f, 0.25f, 1.0f, 0.0f);
        for (auto& run : runs) run->pipeline->clear(request);
        break;
      }
      case 5: {  // glAccum ends the pass
        const RenderState s = state(in);
        const AccumOp op = in.pick<AccumOp>(5);
        const float value = float(int(in.byte()) - 64) / 64.0f;
        for (auto& run : runs) {
          if (!run->pipeline->framebuffer().hasColor()) run->pipeline->clear({.state = s, .color = glm::vec4(0.0f)});
          run->pipeline->accumulate(s, op, value);
        }
        pass.clear();
        break;
      }
      case 6:
        endPass();
        compare(runs, command);
        break;
      default: {  // watch a pixel from the next draw on
        const int x = in.byte() % kWidth, y = in.byte() % kHeight;
        endPass();
        for (auto& run : runs) run->pipeline->watchPixel(x, y, &run->recorder);
        break;
      }
    }
  }
  endPass();
  compare(runs, size_t(-1));
  return 0;
}
