// The fast executor against the reference pipeline: random command streams (draws of random
// triangles in random states, clears in the middle of passes, accumulation, a watched pixel), each
// run on ReferencePipeline and on the fast pipeline with 1, 2, 3 and 8 threads. Every buffer byte
// (which buffers exist, colour float bits, depth codes, stencil, accumulation), every RasterStats
// counter and every pixel-history event must be the same: the reference defines them, the fast
// executor has no semantics of its own (gl/pipeline.h).
//
// The streams are made by a seeded std::mt19937_64 and are the same on every run. A mismatch names
// the seed, the first command after which the buffers differ, and the first differing pixel.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <deque>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "exec/fast_pipeline.h"
#include "gl/lighting.h"
#include "gl/pipeline.h"
#include "support/raster_harness.h"
#include "gl/projection.h"
#include "scene/adjacency.h"
#include "shadow/shadow_volume.h"
#include "shadow/stencil_counting.h"

using namespace shadowref;

namespace {

enum class ShaderKind : uint8_t { None, ColorVarying, Constant, PerPixel, Gouraud };

// The shaders the draws use: made once, shared by every stream (shaders are const and hold no
// per-draw state).
struct Shaders {
  ColorVaryingShader colorVarying;
  ConstantColorShader constant{glm::dvec4(0.25, 0.625, 1.5, 0.5)};
  PerPixelLightingShader perPixel{lighting()};
  GouraudShader gouraud;

  static LightingSetup lighting() {
    LightingSetup s;
    s.material.specular = glm::dvec3(0.5);
    s.material.shininess = 12.0;
    s.globalAmbient = glm::dvec3(0.1);
    PhongLight point;
    point.position = glm::dvec4(0.5, 2.0, 1.0, 1.0);
    point.attenuation = glm::dvec3(1.0, 0.1, 0.01);
    PhongLight spot;
    spot.position = glm::dvec4(-1.0, 1.0, 2.0, 1.0);
    spot.spotDirection = glm::dvec3(0.3, -0.4, -1.0);
    spot.spotCosCutoff = 0.8;
    spot.spotExponent = 4.0;
    PhongLight sun;
    sun.position = glm::dvec4(0.2, 1.0, 0.3, 0.0);
    s.lights = {point, spot, sun};
    s.eye = glm::dvec3(0.0, 0.5, 3.0);
    return s;
  }
  const FragmentShader* get(ShaderKind k) const {
    switch (k) {
      case ShaderKind::None: return nullptr;
      case ShaderKind::ColorVarying: return &colorVarying;
      case ShaderKind::Constant: return &constant;
      case ShaderKind::PerPixel: return &perPixel;
      case ShaderKind::Gouraud: return &gouraud;
    }
    return nullptr;
  }
};

const Shaders& shaders() {
  static const Shaders s;
  return s;
}

struct DrawData {
  RenderState state;
  std::vector<ClipVertex> vertices;
  std::vector<uint32_t> indices;
  ShaderKind shader = ShaderKind::None;
  uint32_t tag = 0;
};

struct Command {
  enum class Kind : uint8_t { Draw, Clear, Accum, EndPass, Watch } kind = Kind::Draw;
  size_t draw = 0;  // Draw: index into Stream::draws
  ClearRequest clear;
  RenderState accumState;
  AccumOp op = AccumOp::Accum;
  float value = 0.0f;
  int x = 0, y = 0;  // Watch: the pixel; x < 0 stops watching
};

struct Stream {
  uint64_t seed = 0;
  int width = 37, height = 29;
  DepthFormat format = DepthFormat::Float32;
  std::deque<DrawData> draws;  // stable addresses: the draws borrow them until their pass ends
  std::vector<Command> commands;
};

// The random source of one stream: TestRandom (the same numbers with every standard library).
class Random {
 public:
  explicit Random(uint64_t seed) : random_(seed) {}
  double uniform(double lo, double hi) { return random_.uniform(lo, hi); }
  int integer(int lo, int hi) { return lo + random_.below(hi - lo + 1); }
  bool chance(double p) { return random_.uniform() < p; }
  template <class E>
  E pick(int count) {
    return E(random_.below(count));
  }

 private:
  testing::TestRandom random_;
};

StencilFaceState randomFace(Random& r) {
  StencilFaceState f;
  f.func = r.pick<CompareFunc>(8);
  f.ref = r.chance(0.8) ? r.integer(0, 4) : r.integer(-3, 300);  // out of range: clamped
  f.mask = r.chance(0.7) ? uint8_t(0xFF) : uint8_t(r.integer(0, 255));
  f.writeMask = r.chance(0.7) ? uint8_t(0xFF) : uint8_t(r.integer(0, 255));
  f.sfail = r.pick<StencilOp>(8);
  f.dpfail = r.pick<StencilOp>(8);
  f.dppass = r.pick<StencilOp>(8);
  return f;
}

Rect randomRect(Random& r, const Stream& s) {
  Rect q;
  q.x = r.integer(-8, s.width - 4);
  q.y = r.integer(-8, s.height - 4);
  q.width = r.integer(0, s.width + 8);
  q.height = r.integer(0, s.height + 8);
  return q;
}

// The kinds of pass the executor has span loops of its own for, and everything else.
enum class PassKind { Random, Counting, DepthOnly, ConstantColor, Lit };

RenderState randomState(Random& r, const Stream& s, PassKind pass) {
  RenderState st;
  st.viewport = {0, 0, s.width, s.height, 0.0, 1.0};
  if (r.chance(0.2)) st.viewport = {r.integer(-10, 10), r.integer(-10, 10), r.integer(1, s.width + 20), r.integer(1, s.height + 20), 0.0, 1.0};
  if (r.chance(0.2)) {
    st.viewport.nearVal = r.uniform(0.0, 0.5);
    st.viewport.farVal = r.uniform(0.5, 1.0);
    if (r.chance(0.3)) std::swap(st.viewport.nearVal, st.viewport.farVal);  // reversed depth range
  }
  st.scissorTest = r.chance(0.25);
  st.scissor = randomRect(r, s);
  st.cull = r.pick<CullMode>(4);
  if (r.chance(0.5)) st.cull = CullMode::None;
  st.frontFace = r.pick<FrontFace>(2);
  st.depthTest = r.chance(0.6);
  st.depthFunc = r.chance(0.5) ? CompareFunc::Less : r.pick<CompareFunc>(8);
  st.depthWrite = r.chance(0.7);
  st.depthClamp = r.chance(0.2);
  st.clipFar = r.chance(0.85);
  if (r.chance(0.25)) st.polygonOffset = {true, r.uniform(-2.0, 2.0), r.uniform(-4.0, 4.0)};
  st.stencilTest = r.chance(0.5);
  st.stencil = {randomFace(r), randomFace(r)};
  if (r.chance(0.3)) st.stencil[1] = st.stencil[0];
  st.blend.enabled = r.chance(0.3);
  st.blend.src = r.pick<BlendFactor>(10);
  st.blend.dst = r.pick<BlendFactor>(10);
  if (r.chance(0.3)) st.colorMask = {r.chance(0.5), r.chance(0.5), r.chance(0.5), r.chance(0.5)};

  switch (pass) {
    case PassKind::Random: break;
    case PassKind::Counting:  // a shadow volume pass: stencil ALWAYS, only wrapping counts
      st.stencilTest = true;
      st.depthWrite = false;
      st.blend.enabled = false;
      for (StencilFaceState& f : st.stencil) {
        const StencilOp ops[] = {StencilOp::Keep, StencilOp::IncrWrap, StencilOp::DecrWrap};
        f.func = CompareFunc::Always;
        f.writeMask = 0xFF;
        f.dpfail = ops[r.integer(0, 2)];
        f.dppass = ops[r.integer(0, 2)];
      }
      break;
    case PassKind::DepthOnly:
      st.stencilTest = false;
      st.depthTest = true;
      st.depthWrite = true;
      break;
    case PassKind::ConstantColor:
      st.stencilTest = false;
      st.blend.enabled = false;
      st.colorMask = {true, true, true, true};
      break;
    case PassKind::Lit:  // the lit pass of a shadow volume frame: stencil EQUAL 0, nothing written
      st.stencilTest = true;
      for (StencilFaceState& f : st.stencil) f = {CompareFunc::Equal, 0, 0xFF, 0xFF, StencilOp::Keep, StencilOp::Keep, StencilOp::Keep};
      st.depthFunc = CompareFunc::LEqual;
      st.depthWrite = false;
      break;
  }
  return st;
}

// A clip-space vertex. Most lie in or near the view volume; some are beyond the near or far plane,
// far outside the guard band, at w near 0 or below, or exactly on a pixel centre (edges through
// centres exercise the top-left rule).
ClipVertex randomVertex(Random& r, const Stream& s) {
  ClipVertex v;
  const int kind = r.integer(0, 19);
  double w = r.uniform(0.3, 3.0);
  double x = r.uniform(-1.3, 1.3), y = r.uniform(-1.3, 1.3), z = r.uniform(-1.1, 1.1);
  if (kind == 0) z = r.uniform(-3.0, 3.0);                   // across near / far
  if (kind == 1) x = r.uniform(-4e6, 4e6);                   // beyond the guard band
  if (kind == 2) w = r.chance(0.5) ? r.uniform(-1e-6, 1e-6) : 0.0;  // at or about infinity
  if (kind == 3) w = -r.uniform(0.1, 2.0);                   // behind the eye
  if (kind >= 4 && kind <= 7) {                              // on a pixel centre
    x = (2.0 * (r.integer(0, s.width - 1) + 0.5)) / s.width - 1.0;
    y = (2.0 * (r.integer(0, s.height - 1) + 0.5)) / s.height - 1.0;
    w = 1.0;
  }
  v.position = glm::dvec4(x * w, y * w, z * w, w);
  if (kind == 2) v.position = glm::dvec4(x, y, z, w);  // a direction: finite x, y, z at w about 0
  for (double& a : v.varyings) a = r.uniform(-0.25, 1.25);
  // The lighting shaders read a position (0..2) and a normal (3..5).
  const glm::dvec3 n = glm::normalize(glm::dvec3(r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(0.1, 1)));
  v.varyings[3] = n.x;
  v.varyings[4] = n.y;
  v.varyings[5] = n.z;
  return v;
}

DrawData randomDraw(Random& r, const Stream& s, PassKind pass, uint32_t tag) {
  DrawData d;
  d.tag = tag;
  d.state = randomState(r, s, pass);
  switch (pass) {
    case PassKind::Counting:
    case PassKind::DepthOnly: d.shader = ShaderKind::None; break;
    case PassKind::ConstantColor: d.shader = ShaderKind::Constant; break;
    default: d.shader = r.pick<ShaderKind>(5);
  }
  const int triangles = r.integer(1, pass == PassKind::Counting ? 60 : 12);
  if (r.chance(0.5)) {  // indexed, vertices shared between triangles
    const int count = r.integer(3, 2 * triangles + 3);
    for (int i = 0; i < count; ++i) d.vertices.push_back(randomVertex(r, s));
    for (int i = 0; i < 3 * triangles; ++i) d.indices.push_back(uint32_t(r.integer(0, count - 1)));
  } else {
    for (int i = 0; i < 3 * triangles; ++i) d.vertices.push_back(randomVertex(r, s));
    if (r.chance(0.2)) d.vertices.push_back(randomVertex(r, s));  // an incomplete last triangle
    // Some triangles tiny or degenerate: the second and third corners moved onto the first.
    for (int i = 0; i < triangles; ++i) {
      if (!r.chance(0.15)) continue;
      ClipVertex* t = &d.vertices[size_t(3 * i)];
      const double scale = r.chance(0.5) ? 0.0 : 1e-3;
      for (int k = 1; k < 3; ++k) t[k].position = t[0].position + scale * (t[k].position - t[0].position);
    }
  }
  // A shared edge in every other draw: a quad of two triangles, the second listing the edge reversed.
  if (d.indices.empty() && r.chance(0.5)) {
    const ClipVertex a = randomVertex(r, s), b = randomVertex(r, s), c = randomVertex(r, s), e = randomVertex(r, s);
    for (const ClipVertex& v : {a, b, c, c, b, e}) d.vertices.insert(d.vertices.begin(), v);
  }
  return d;
}

ClearRequest randomClear(Random& r, const Stream& s) {
  ClearRequest c;
  c.state.scissorTest = r.chance(0.4);
  c.state.scissor = randomRect(r, s);
  if (r.chance(0.3)) c.state.colorMask = {r.chance(0.5), r.chance(0.5), r.chance(0.5), r.chance(0.5)};
  if (r.chance(0.3)) c.state.depthWrite = false;
  if (r.chance(0.3)) c.state.stencil[FrontFacing].writeMask = uint8_t(r.integer(0, 255));
  if (r.chance(0.6)) c.color = glm::vec4(float(r.uniform(-0.5, 1.5)), float(r.uniform(0, 1)), float(r.uniform(0, 1)), float(r.uniform(0, 1)));
  if (r.chance(0.6)) c.depth = r.chance(0.7) ? 1.0 : r.uniform(-0.2, 1.2);
  if (r.chance(0.6)) c.stencil = r.chance(0.7) ? 0 : r.integer(-5, 300);
  if (r.chance(0.15)) c.accum = glm::vec4(float(r.uniform(-1, 1)));
  return c;
}

Stream makeStream(uint64_t seed) {
  Random r(seed);
  Stream s;
  s.seed = seed;
  // Small, so that hundreds of streams run in a second or two; the taller ones are cut into
  // several bands of rows (at least 16 rows each) when the executor has threads.
  const int sizes[][2] = {{37, 29}, {37, 29}, {29, 37}, {61, 53}, {23, 71}, {97, 83}};
  const int size = r.integer(0, 5);
  s.width = sizes[size][0];
  s.height = sizes[size][1];
  s.format = r.chance(0.5) ? DepthFormat::Float32 : DepthFormat::Unorm24;
  auto add = [&](Command::Kind kind) -> Command& {
    s.commands.emplace_back();
    s.commands.back().kind = kind;
    return s.commands.back();
  };
  // Half the streams watch a pixel from the start: a watched pass is never counted in any order
  // (the executor's counting flushes), so the other half reaches those.
  if (r.chance(0.5)) {
    Command& w = add(Command::Kind::Watch);
    w.x = r.integer(0, s.width - 1);
    w.y = r.integer(0, s.height - 1);
  }
  const int passes = r.integer(2, 9);
  uint32_t tag = 0;
  for (int p = 0; p < passes; ++p) {
    if (r.chance(0.6)) add(Command::Kind::Clear).clear = randomClear(r, s);
    const PassKind kind = r.pick<PassKind>(5);
    const int draws = r.integer(1, kind == PassKind::Counting ? 10 : 5);
    for (int i = 0; i < draws; ++i) {
      s.draws.push_back(randomDraw(r, s, r.chance(0.85) ? kind : PassKind::Random, tag++));
      add(Command::Kind::Draw).draw = s.draws.size() - 1;
      if (r.chance(0.1)) add(Command::Kind::Clear).clear = randomClear(r, s);  // in the middle of a pass
      if (r.chance(0.05)) {
        Command& w = add(Command::Kind::Watch);
        w.x = r.chance(0.2) ? -1 : r.integer(0, s.width - 1);
        w.y = r.integer(0, s.height - 1);
      }
    }
    if (r.chance(0.25)) {
      Command& a = add(Command::Kind::Accum);
      a.accumState.scissorTest = r.chance(0.3);
      a.accumState.scissor = randomRect(r, s);
      if (r.chance(0.3)) a.accumState.colorMask = {r.chance(0.5), r.chance(0.5), r.chance(0.5), r.chance(0.5)};
      a.op = r.pick<AccumOp>(5);
      a.value = float(r.uniform(-1.0, 2.0));
    } else if (r.chance(0.5)) {
      add(Command::Kind::EndPass);
    }
  }
  return s;
}

class Recorder final : public FragmentObserver {
 public:
  void onFragment(const FragmentEvent& e) override { events.push_back(e); }
  std::vector<FragmentEvent> events;
};

struct Outcome {
  std::unique_ptr<Framebuffer> fb;
  RasterStats stats;
  std::vector<FragmentEvent> events;
};

// Runs commands [0, count) of the stream on a pipeline of that kind and thread count; `inspect`
// sees the pipeline at the end.
Outcome run(const Stream& s, size_t count, PipelineKind kind, int threads,
            const std::function<void(Pipeline&)>& inspect = {}) {
  Outcome out;
  out.fb = std::make_unique<Framebuffer>(s.width, s.height, s.format);
  Recorder recorder;
  {
    std::unique_ptr<Pipeline> pipeline = makePipeline(kind, *out.fb, threads);
    REQUIRE(pipeline);
    for (size_t i = 0; i < count; ++i) {
      const Command& c = s.commands[i];
      switch (c.kind) {
        case Command::Kind::Draw: {
          const DrawData& d = s.draws[c.draw];
          DrawCall call;
          call.state = &d.state;
          call.vertices = d.vertices;
          call.indices = d.indices;
          call.shader = shaders().get(d.shader);
          call.tag = d.tag;
          pipeline->draw(call);
          break;
        }
        case Command::Kind::Clear: pipeline->clear(c.clear); break;
        case Command::Kind::Accum: pipeline->accumulate(c.accumState, c.op, c.value); break;
        case Command::Kind::EndPass: pipeline->endPass(); break;
        case Command::Kind::Watch: pipeline->watchPixel(c.x, c.y, c.x < 0 ? nullptr : &recorder); break;
      }
    }
    pipeline->framebuffer();  // ends the last pass: the stats count every draw
    out.stats = pipeline->stats();
    if (inspect) inspect(*pipeline);
  }
  out.events = recorder.events;
  return out;
}

template <class T>
bool sameBits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

// The first difference between two framebuffers, or "".
std::string bufferDifference(const Framebuffer& a, const Framebuffer& b) {
  std::ostringstream out;
  auto pixel = [&](const char* buffer, size_t i) {
    out << buffer << " differs first at pixel (" << i % size_t(a.width()) << ", " << i / size_t(a.width()) << ")";
    return out.str();
  };
  if (a.hasColor() != b.hasColor() || a.hasDepth() != b.hasDepth() || a.hasStencil() != b.hasStencil() ||
      a.hasAccum() != b.hasAccum())
    return "the buffers made differ (colour, depth, stencil, accumulation)";
  for (size_t i = 0; a.hasColor() && i < a.pixelCount(); ++i)
    if (!sameBits(a.color()[i], b.color()[i])) return pixel("colour", i);
  for (size_t i = 0; a.hasDepth() && i < a.pixelCount(); ++i)
    if (a.depthCodes()[i] != b.depthCodes()[i]) return pixel("depth", i);
  for (size_t i = 0; a.hasStencil() && i < a.pixelCount(); ++i)
    if (a.stencil()[i] != b.stencil()[i]) return pixel("stencil", i);
  for (size_t i = 0; a.hasAccum() && i < a.pixelCount(); ++i)
    if (!sameBits(a.accum()[i], b.accum()[i])) return pixel("accumulation", i);
  return "";
}

std::string statsDifference(const RasterStats& a, const RasterStats& b) {
  std::ostringstream out;
  auto field = [&](const char* name, uint64_t x, uint64_t y) {
    if (x != y && out.tellp() == 0) out << "stats." << name << ": reference " << x << ", fast " << y;
  };
  field("drawCalls", a.drawCalls, b.drawCalls);
  field("trianglesIn", a.trianglesIn, b.trianglesIn);
  field("trianglesClipped", a.trianglesClipped, b.trianglesClipped);
  field("trianglesCulled", a.trianglesCulled, b.trianglesCulled);
  field("trianglesRasterized", a.trianglesRasterized, b.trianglesRasterized);
  field("fragments", a.fragments, b.fragments);
  field("stencilFailed", a.stencilFailed, b.stencilFailed);
  field("depthFailed", a.depthFailed, b.depthFailed);
  field("stencilWrites", a.stencilWrites, b.stencilWrites);
  field("colorWrites", a.colorWrites, b.colorWrites);
  return out.str();
}

bool sameEvent(const FragmentEvent& a, const FragmentEvent& b) {
  return a.x == b.x && a.y == b.y && a.drawIndex == b.drawIndex && a.drawTag == b.drawTag && a.facing == b.facing &&
         sameBits(a.depth, b.depth) && sameBits(a.storedDepth, b.storedDepth) && a.scissorPassed == b.scissorPassed &&
         a.stencilPassed == b.stencilPassed && a.depthPassed == b.depthPassed && a.stencilBefore == b.stencilBefore &&
         a.stencilAfter == b.stencilAfter && sameBits(a.colorBefore, b.colorBefore) && sameBits(a.colorAfter, b.colorAfter);
}

std::string describe(const FragmentEvent& e) {
  std::ostringstream out;
  out.precision(17);
  out << "{(" << e.x << ", " << e.y << ") draw " << e.drawIndex << " tag " << e.drawTag << " facing " << int(e.facing)
      << " depth " << e.depth << " stored " << e.storedDepth << " passed " << e.scissorPassed << e.stencilPassed
      << e.depthPassed << " stencil " << int(e.stencilBefore) << "->" << int(e.stencilAfter) << " colour ("
      << e.colorBefore.r << ", " << e.colorBefore.g << ", " << e.colorBefore.b << ", " << e.colorBefore.a << ") -> ("
      << e.colorAfter.r << ", " << e.colorAfter.g << ", " << e.colorAfter.b << ", " << e.colorAfter.a << ")}";
  return out.str();
}

std::string eventsDifference(const std::vector<FragmentEvent>& a, const std::vector<FragmentEvent>& b) {
  std::ostringstream out;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    if (!sameEvent(a[i], b[i])) {
      out << "pixel-history event " << i << " differs: reference " << describe(a[i]) << ", fast " << describe(b[i]);
      return out.str();
    }
  }
  if (a.size() != b.size()) out << "pixel history: reference " << a.size() << " events, fast " << b.size();
  return out.str();
}

std::string difference(const Outcome& ref, const Outcome& fast) {
  std::string d = bufferDifference(*ref.fb, *fast.fb);
  if (d.empty()) d = statsDifference(ref.stats, fast.stats);
  if (d.empty()) d = eventsDifference(ref.events, fast.events);
  return d;
}

// The first command after which the two pipelines' buffers differ (replaying prefixes).
size_t firstDifferingCommand(const Stream& s, int threads) {
  for (size_t n = 1; n <= s.commands.size(); ++n)
    if (!difference(run(s, n, PipelineKind::Reference, 1), run(s, n, PipelineKind::Fast, threads)).empty()) return n - 1;
  return s.commands.size();
}

const char* commandName(Command::Kind k) {
  switch (k) {
    case Command::Kind::Draw: return "draw";
    case Command::Kind::Clear: return "clear";
    case Command::Kind::Accum: return "accumulate";
    case Command::Kind::EndPass: return "endPass";
    case Command::Kind::Watch: return "watchPixel";
  }
  return "?";
}

// A command in a line: enough of it to rebuild the failing case by hand.
std::string describe(const Stream& s, const Command& c) {
  std::ostringstream out;
  out << commandName(c.kind);
  if (c.kind == Command::Kind::Draw) {
    const DrawData& d = s.draws[c.draw];
    const RenderState& st = d.state;
    out << " tag " << d.tag << ": " << d.vertices.size() << " vertices, " << d.indices.size() << " indices, shader "
        << int(d.shader) << ", depth test " << st.depthTest << " " << name(st.depthFunc) << " write " << st.depthWrite
        << " clamp " << st.depthClamp << ", stencil test " << st.stencilTest << " front " << name(st.stencil[0].func)
        << "/" << name(st.stencil[0].sfail) << "/" << name(st.stencil[0].dpfail) << "/" << name(st.stencil[0].dppass)
        << " back " << name(st.stencil[1].func) << "/" << name(st.stencil[1].sfail) << "/" << name(st.stencil[1].dpfail)
        << "/" << name(st.stencil[1].dppass) << ", blend " << st.blend.enabled << ", scissor " << st.scissorTest
        << ", cull " << int(st.cull);
  } else if (c.kind == Command::Kind::Clear) {
    const ClearRequest& r = c.clear;
    out << ":" << (r.color ? " colour" : "") << (r.depth ? " depth " + std::to_string(*r.depth) : "")
        << (r.stencil ? " stencil " + std::to_string(*r.stencil) : "") << (r.accum ? " accum" : "") << ", scissor "
        << r.state.scissorTest << ", depth mask " << r.state.depthWrite;
  } else if (c.kind == Command::Kind::Watch) {
    out << " (" << c.x << ", " << c.y << ")";
  }
  return out.str();
}

void checkStream(const Stream& s) {
  const uint64_t seed = s.seed;
  const Outcome ref = run(s, s.commands.size(), PipelineKind::Reference, 1);
  for (const int threads : {1, 2, 3, 8}) {
    const Outcome fast = run(s, s.commands.size(), PipelineKind::Fast, threads);
    const std::string d = difference(ref, fast);
    if (d.empty()) continue;
    const size_t at = firstDifferingCommand(s, threads);
    std::ostringstream out;
    out << "seed " << seed << ", " << threads << " threads, " << s.width << "x" << s.height << ": " << d
        << "; first after command " << at;
    for (size_t i = 0; i <= at && i < s.commands.size(); ++i) out << "\n  " << i << ": " << describe(s, s.commands[i]);
    FAIL(out.str());
  }
}

void checkStream(uint64_t seed) { checkStream(makeStream(seed)); }

// The meshes users write that are not closed outward solids (shadow/volume_casting.h): an open
// tent (no floor, front open), a lone triangle, three fins on one edge (non-manifold), a cube
// wound inside out, a cube with one face reversed, and a cube wound outwards with a half-size
// cube wound inside out beside it in the same mesh (closed, total volume positive).
std::vector<Mesh> irregularMeshes() {
  auto mesh = [](std::vector<glm::dvec3> p, std::vector<glm::uvec3> t) {
    Mesh m;
    m.positions = std::move(p);
    m.triangles = std::move(t);
    computeSmoothNormals(m);
    buildAdjacency(m);
    return m;
  };
  const std::vector<glm::dvec3> cube{{-0.5, -0.5, -0.5}, {0.5, -0.5, -0.5}, {0.5, 0.5, -0.5}, {-0.5, 0.5, -0.5},
                                     {-0.5, -0.5, 0.5},  {0.5, -0.5, 0.5},  {0.5, 0.5, 0.5},  {-0.5, 0.5, 0.5}};
  // Clockwise seen from outside; the second cube has its top (3 7 8 4 in OBJ terms) the right way.
  const std::vector<glm::uvec3> insideOut{{0, 1, 2}, {0, 2, 3}, {7, 6, 5}, {7, 5, 4}, {4, 5, 1}, {4, 1, 0},
                                          {2, 6, 7}, {2, 7, 3}, {3, 7, 4}, {3, 4, 0}, {5, 6, 2}, {5, 2, 1}};
  std::vector<glm::dvec3> mixed = cube;
  std::vector<glm::uvec3> mixedTriangles;
  for (const glm::uvec3& t : insideOut) mixedTriangles.push_back({t.x, t.z, t.y});  // outward
  for (const glm::dvec3& p : cube) mixed.push_back(p * 0.5 + glm::dvec3(1.0, -0.25, 0.0));
  for (const glm::uvec3& t : insideOut) mixedTriangles.push_back(t + glm::uvec3(8));
  std::vector<glm::uvec3> flipped = insideOut;
  for (size_t t = 0; t < flipped.size(); ++t)
    if (t != 6 && t != 7) std::swap(flipped[t].y, flipped[t].z);
  return {mesh({{0, 1.2, 1.2}, {1, 0, 1.2}, {1, 0, -1.2}, {0, 1.2, -1.2}, {-1, 0, -1.2}, {-1, 0, 1.2}},
               {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {4, 3, 2}}),
          mesh({{-0.6, 0, 0}, {0.6, 0, 0}, {0, 0.9, 0}}, {{0, 1, 2}}),
          mesh({{0, 0, 0}, {0, 1, 0}, {0.6, 0.5, 0}, {-0.3, 0.5, 0.52}, {-0.3, 0.5, -0.52}}, {{0, 2, 1}, {0, 3, 1}, {0, 4, 1}}),
          mesh(cube, insideOut), mesh(cube, flipped), mesh(mixed, mixedTriangles)};
}

// A shadow-volume frame over one of those meshes and a ground quad, as volume_renderer.cpp draws
// it: the depth pass, the mesh's volume for a random light counted z-pass or z-fail (two-sided
// stencil or two culled passes), and the lit pass where the stencil is 0. Seen from a random eye
// around the mesh under P_inf, at a random size and depth format.
Stream volumeStream(uint64_t seed) {
  Random r(seed);
  static const std::vector<Mesh> meshes = irregularMeshes();
  const Mesh& mesh = meshes[size_t(r.integer(0, int(meshes.size()) - 1))];
  Stream s;
  s.seed = seed;
  s.width = r.integer(24, 64);
  s.height = r.integer(20, 48);
  s.format = r.chance(0.5) ? DepthFormat::Float32 : DepthFormat::Unorm24;
  const double angle = r.uniform(0.0, 6.283185307179586);
  const glm::dvec3 eye(3.5 * std::cos(angle), r.uniform(0.8, 3.0), 3.5 * std::sin(angle));
  const glm::dmat4 toClip = infinitePerspective(50.0, double(s.width) / s.height, 0.1) *
                            lookAt(eye, glm::dvec3(0.0, 0.3, 0.0), glm::dvec3(0.0, 1.0, 0.0));
  const glm::dvec4 light = r.chance(0.25) ? glm::dvec4(glm::normalize(glm::dvec3(r.uniform(-1, 1), 1.0, r.uniform(-1, 1))), 0.0)
                                          : glm::dvec4(r.uniform(-3, 3), r.uniform(1.5, 4), r.uniform(-3, 3), 1.0);
  const bool zfail = r.chance(0.5);
  const ShadowVolume volume = buildShadowVolume(mesh, light, SilhouetteAlgorithm::Kuhn, zfail);

  RenderState base;
  base.viewport = {0, 0, s.width, s.height, 0.0, 1.0};
  base.clipFar = false;
  base.cull = CullMode::Back;
  base.depthTest = true;
  base.depthFunc = CompareFunc::Less;
  auto draw = [&](const RenderState& state, std::vector<ClipVertex> vertices, std::vector<uint32_t> indices,
                  ShaderKind shader) {
    s.draws.push_back({state, std::move(vertices), std::move(indices), shader, uint32_t(s.draws.size())});
    Command c;
    c.draw = s.draws.size() - 1;
    s.commands.push_back(c);
  };
  auto endPass = [&] {
    Command c;
    c.kind = Command::Kind::EndPass;
    s.commands.push_back(c);
  };
  std::vector<ClipVertex> scene;
  std::vector<uint32_t> sceneIndices;
  auto vertex = [&](const glm::dvec4& p) {
    ClipVertex v;
    v.position = toClip * p;
    for (double& a : v.varyings) a = 0.5;
    return v;
  };
  for (const glm::dvec3& p : mesh.positions) scene.push_back(vertex(glm::dvec4(p, 1.0)));
  for (const glm::uvec3& t : mesh.triangles) sceneIndices.insert(sceneIndices.end(), {t.x, t.y, t.z});
  const uint32_t g = uint32_t(scene.size());
  for (const glm::dvec3& p : {glm::dvec3(-4, -0.01, -4), glm::dvec3(-4, -0.01, 4), glm::dvec3(4, -0.01, 4), glm::dvec3(4, -0.01, -4)})
    scene.push_back(vertex(glm::dvec4(p, 1.0)));
  sceneIndices.insert(sceneIndices.end(), {g, g + 1, g + 2, g, g + 2, g + 3});

  Command clear;
  clear.kind = Command::Kind::Clear;
  clear.clear = {.state = base, .color = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), .depth = 1.0, .stencil = 0};
  s.commands.push_back(clear);
  draw(base, scene, sceneIndices, ShaderKind::Constant);
  endPass();
  std::vector<ClipVertex> volumeVertices;
  for (const glm::dvec4& p : volume.positions) volumeVertices.push_back(vertex(p));
  std::vector<uint32_t> volumeIndices;
  for (VolumePart part : {VolumePart::Side, VolumePart::FrontCap, VolumePart::BackCap})
    for (const glm::uvec3& t : volume.part(part)) volumeIndices.insert(volumeIndices.end(), {t.x, t.y, t.z});
  for (const RenderState& state : volumePassStates(base, zfail ? StencilCounting::ZFail : StencilCounting::ZPass,
                                                   CountingOptions{r.chance(0.7), true}))
    draw(state, volumeVertices, volumeIndices, ShaderKind::None);
  endPass();
  RenderState lit = base;
  lit.depthFunc = CompareFunc::LEqual;
  lit.depthWrite = false;
  lit.stencilTest = true;
  for (StencilFaceState& f : lit.stencil) f = {CompareFunc::Equal, 0, 0xFF, 0xFF, StencilOp::Keep, StencilOp::Keep, StencilOp::Keep};
  lit.blend = {true, BlendFactor::One, BlendFactor::One};
  draw(lit, scene, sceneIndices, ShaderKind::Constant);
  endPass();
  return s;
}

}  // namespace

TEST_CASE("the fast pipeline gives the reference's bytes, counters and history for random streams",
          "[differential]") {
  for (uint64_t seed = 1; seed <= 300; ++seed) checkStream(seed);
}

TEST_CASE("the fast pipeline gives the reference's bytes for shadow-volume frames of open, non-manifold, "
          "inconsistently wound and inside-out meshes", "[differential]") {
  size_t stencilWrites = 0;
  for (uint64_t seed = 1; seed <= 60; ++seed) {
    const Stream s = volumeStream(seed);
    checkStream(s);
    stencilWrites += run(s, s.commands.size(), PipelineKind::Reference, 1).stats.stencilWrites;
  }
  CHECK(stencilWrites > 1000);  // the volumes reach the pixels
}

TEST_CASE("differential streams reach every pass kind and make fragments", "[differential]") {
  // The comparison above is only worth what the streams exercise: over the seeds, fragments are
  // drawn, stencil tests fail and write, depth tests fail, colour is written, triangles are
  // clipped and culled, and the watched pixel sees events.
  RasterStats total;
  size_t events = 0;
  uint64_t byTriangles = 0, byBands = 0;
  for (uint64_t seed = 1; seed <= 300; ++seed) {
    const Stream s = makeStream(seed);
    if (seed <= 60) {
      const Outcome o = run(s, s.commands.size(), PipelineKind::Reference, 1);
      total += o.stats;
      events += o.events.size();
    }
    // The executor's counting flushes (shadow-volume passes counted in any order) are reached.
    run(s, s.commands.size(), PipelineKind::Fast, 3, [&](Pipeline& p) {
      Renderer& r = dynamic_cast<FastPipeline&>(p).renderer();
      byTriangles += r.flushesCountedByTriangles();
      byBands += r.flushesCountedByBands();
    });
  }
  CHECK(byTriangles > 0);
  CHECK(byBands > 0);
  CHECK(total.fragments > 10000);
  CHECK(total.stencilFailed > 100);
  CHECK(total.stencilWrites > 100);
  CHECK(total.depthFailed > 100);
  CHECK(total.colorWrites > 1000);
  CHECK(total.trianglesClipped > 50);
  CHECK(total.trianglesCulled > 50);
  CHECK(events > 20);
}
