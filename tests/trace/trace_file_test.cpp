// The trace format (docs/trace-format.md) written by the recorder and read back: a hand-made frame
// through the recording pipeline gives exactly the commands it was given, replays to the recorded
// buffers on both pipelines, and every malformed or truncated variant is refused with the byte
// offset of what is wrong.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>

#include "gl/fragment_shader.h"
#include "gl/lighting.h"
#include "support/cli_run.h"
#include "trace/replay_target.h"
#include "trace/trace_file.h"
#include "trace/trace_recorder.h"
#include "trace/trace_replay.h"

namespace shadowref::trace {

namespace {

// Two overlapping triangles with colours, counted in the stencil buffer (INCR on depth pass), a
// constant-colour triangle blended ONE/ONE, and an accumulation LOAD / RETURN.
std::vector<uint8_t> handMadeTrace() {
  TraceRecorder recorder;
  const std::unique_ptr<PipelineMaker> inner = makePipelineMaker(PipelineKind::Reference);
  const std::unique_ptr<PipelineMaker> maker = recorder.wrap(*inner);
  Framebuffer fb(8, 6);
  {
    const std::unique_ptr<Pipeline> p = maker->make(fb);
    RenderState s;
    s.viewport = {0, 0, 8, 6, 0.0, 1.0};
    s.depthTest = true;
    s.stencilTest = true;
    for (StencilFaceState& f : s.stencil) f.dppass = StencilOp::Incr;
    p->clear({.state = s, .color = glm::vec4(0.1f, 0.2f, 0.3f, 1.0f), .depth = 1.0, .stencil = 0, .accum = glm::vec4(0.0f)});
    std::vector<ClipVertex> v(6);
    const glm::dvec4 corners[6] = {{-1, -1, 0.5, 1}, {1, -1, 0.5, 1}, {-1, 1, 0.5, 1},
                                   {-0.5, -0.5, 0.25, 1}, {1, 0, 0.25, 1}, {0, 1, 0.25, 1}};
    for (int i = 0; i < 6; ++i) {
      v[size_t(i)].position = corners[i];
      v[size_t(i)].varyings = {i / 6.0, 1.0 - i / 6.0, 0.5, 1.0};
    }
    const std::vector<uint32_t> indices = {0, 1, 2, 3, 4, 5};
    const ColorVaryingShader colours;
    DrawCall call;
    call.state = &s;
    call.vertices = v;
    call.indices = indices;
    call.shader = &colours;
    call.tag = 7;
    p->draw(call);
    p->endPass();
    RenderState blend = s;
    blend.stencilTest = false;
    blend.depthTest = false;
    blend.blend = {true, BlendFactor::One, BlendFactor::One};
    const ConstantColorShader grey(glm::dvec4(0.25, 0.25, 0.25, 1.0));
    DrawCall second = call;
    second.state = &blend;
    second.indices = {};
    second.vertices = std::span<const ClipVertex>(v).subspan(3, 3);
    second.shader = &grey;
    p->draw(second);
    p->accumulate(s, AccumOp::Load, 0.5f);
    p->accumulate(s, AccumOp::Return, 2.0f);
  }
  return recorder.finish();
}

uint32_t readU32(const std::vector<uint8_t>& b, size_t at) {
  uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= uint32_t(b[at + size_t(i)]) << (8 * i);
  return v;
}

// The offset of the first record of `type` (after the 12-byte header).
size_t findRecord(const std::vector<uint8_t>& b, RecordType type) {
  size_t at = 12;
  while (at < b.size()) {
    if (b[at] == uint8_t(type)) return at;
    at += 5 + readU32(b, at + 1);
  }
  FAIL("no such record");
  return 0;
}

}  // namespace

TEST_CASE("trace: a recorded frame reads back as the commands it was given", "[trace]") {
  const std::vector<uint8_t> bytes = handMadeTrace();
  REQUIRE(std::memcmp(bytes.data(), "SRTRACE\0", 8) == 0);
  REQUIRE(readU32(bytes, 8) == kVersion);
  const Trace t = parseTrace(bytes);
  REQUIRE(t.targets.size() == 1);
  CHECK(t.targets[0].width == 8);
  CHECK(t.targets[0].height == 6);
  REQUIRE(t.shaders.size() == 2);
  CHECK(t.shaders[0].description.kind == ShaderKind::ColorVarying);
  CHECK(t.shaders[1].description.kind == ShaderKind::Constant);
  CHECK(t.shaders[1].description.color == glm::dvec4(0.25, 0.25, 0.25, 1.0));
  // clear, draw, end of pass, draw, accum, accum (the result record follows, no end of pass)
  REQUIRE(t.commands.size() == 6);
  const auto& clear = std::get<ClearCommand>(t.commands[0].what);
  CHECK(clear.request.color == glm::vec4(0.1f, 0.2f, 0.3f, 1.0f));
  CHECK(clear.request.stencil == 0);
  const auto& draw = std::get<DrawCommand>(t.commands[1].what);
  CHECK(draw.tag == 7);
  CHECK(draw.varyingCount == 4);
  REQUIRE(draw.vertices.size() == 6);
  CHECK(draw.vertices[4].position == glm::dvec4(1, 0, 0.25, 1));
  CHECK(draw.vertices[5].varyings[0] == 5.0 / 6.0);
  CHECK(draw.indices == std::vector<uint32_t>{0, 1, 2, 3, 4, 5});
  CHECK(draw.state.stencil[1].dppass == StencilOp::Incr);
  CHECK(std::holds_alternative<EndPassCommand>(t.commands[2].what));
  const auto& second = std::get<DrawCommand>(t.commands[3].what);
  CHECK(second.state.blend.enabled);
  CHECK(second.indices.empty());
  CHECK(second.vertices.size() == 3);
  CHECK(second.shader == 1);
  CHECK(std::get<AccumCommand>(t.commands[5].what).op == AccumOp::Return);
  CHECK(std::get<AccumCommand>(t.commands[5].what).value == 2.0f);
  REQUIRE(t.results[0]);
  // Pixel (1, 0), NDC (-0.625, -0.833), lies only in the first triangle (x + y < 0): stencil 1;
  // pixel (3, 2), NDC (-0.125, -0.167), in both (the second is nearer): 2; pixel (7, 0) in none.
  CHECK(t.results[0]->stencil[0 * 8 + 1] == 1);
  CHECK(t.results[0]->stencil[2 * 8 + 3] == 2);
  CHECK(t.results[0]->stencil[0 * 8 + 7] == 0);
}

TEST_CASE("trace: the hand-made frame replays to its recorded bytes on both pipelines", "[trace]") {
  const Trace t = parseTrace(handMadeTrace());
  for (PipelineKind kind : {PipelineKind::Reference, PipelineKind::Fast}) {
    const ReplayResult r = replayOnShadowref(t, kind, 3, ReplayMode::Exact);
    REQUIRE(r.buffers.size() == 1);
    const Buffers& e = *t.results[0];
    CHECK(r.buffers[0].color == e.color);
    CHECK(r.buffers[0].depth == e.depth);
    CHECK(r.buffers[0].stencil == e.stencil);
    CHECK(r.buffers[0].accum == e.accum);
  }
}

TEST_CASE("trace: every truncation is refused at or before its end, never past it", "[trace]") {
  const std::vector<uint8_t> bytes = handMadeTrace();
  for (size_t n = 0; n < bytes.size(); n += (n < 200 ? 1 : 37)) {
    const std::vector<uint8_t> cut(bytes.begin(), bytes.begin() + std::ptrdiff_t(n));
    try {
      parseTrace(cut);
      FAIL("a trace cut to " << n << " bytes was accepted");
    } catch (const TraceError& e) {
      CHECK(e.offset() <= n);
    }
  }
}

TEST_CASE("trace: malformed values are refused with the offset of the value", "[trace]") {
  const std::vector<uint8_t> good = handMadeTrace();
  const auto refuse = [](std::vector<uint8_t> b, uint64_t offset, const std::string& words) {
    try {
      parseTrace(b);
      FAIL("accepted");
    } catch (const TraceError& e) {
      CHECK(e.offset() == offset);
      CHECK_THAT(e.what(), Catch::Contains(words));
      CHECK_THAT(e.what(), Catch::StartsWith("byte " + std::to_string(offset) + ": "));
    }
  };
  SECTION("magic") {
    std::vector<uint8_t> b = good;
    b[0] = 'X';
    refuse(b, 0, "not a shadowref trace");
  }
  SECTION("version") {
    std::vector<uint8_t> b = good;
    b[8] = 9;
    refuse(b, 8, "format version 9");
  }
  SECTION("a vertex count beyond the record") {
    std::vector<uint8_t> b = good;
    const size_t draw = findRecord(b, RecordType::Draw);
    // type, length, target, state (101 bytes), tag, shader, varying count
    const size_t count = draw + 5 + 4 + 101 + 4 + 4 + 1;
    REQUIRE(readU32(b, count) == 6);
    b[count + 3] = 0x40;  // 2^30 + 6 vertices
    refuse(b, count, "vertex count 1073741830 needs");
  }
  SECTION("an index out of range") {
    std::vector<uint8_t> b = good;
    const size_t draw = findRecord(b, RecordType::Draw);
    const size_t firstIndex = draw + 5 + 4 + 101 + 4 + 4 + 1 + 4 + 6 * 8 * 8 + 4;
    REQUIRE(readU32(b, firstIndex + 4) == 1);
    b[firstIndex + 4] = 6;
    refuse(b, firstIndex + 4, "index 6 of a draw of 6 vertices");
  }
  SECTION("an enum out of range") {
    std::vector<uint8_t> b = good;
    const size_t draw = findRecord(b, RecordType::Draw);
    const size_t cull = draw + 5 + 4 + 16 + 16 + 1 + 16;
    REQUIRE(b[cull] == 0);
    b[cull] = 4;
    refuse(b, cull, "cull mode is 4");
  }
  SECTION("a framebuffer beyond the limits") {
    std::vector<uint8_t> b = good;
    const size_t target = findRecord(b, RecordType::Target);
    b[target + 5] = 0xFF;
    b[target + 6] = 0xFF;  // width 65535
    refuse(b, target + 5, "framebuffer width 65535 is outside");
  }
  SECTION("an unknown record") {
    std::vector<uint8_t> b = good;
    const size_t end = b.size() - 5;
    REQUIRE(b[end] == 'Z');
    b[end] = 'Q';
    refuse(b, end, "unknown record type 81");
  }
}

// A framebuffer object has no accumulation buffer: the hand-made frame (LOAD, RETURN) is refused
// on EGL with the reason, and replays on OSMesa, whose context has one.
TEST_CASE("trace: a frame with glAccum is refused on egl:, replayed on osmesa:", "[trace][egl]") {
  if (!osmesaAvailable() || !eglAvailable()) {
    WARN("this build has no OSMesa or no EGL");
    return;
  }
  const Trace t = parseTrace(handMadeTrace());
  CHECK_THROWS_WITH(replayOn(t, *parseReplayTarget("egl:llvmpipe"), ReplayMode::FixedFunction, 1),
                    Catch::Contains("framebuffer 0 uses the accumulation buffer, which this GL's framebuffer lacks"));
  const ReplayResult r = replayOn(t, *parseReplayTarget("osmesa:llvmpipe"), ReplayMode::FixedFunction, 1);
  REQUIRE(r.buffers.size() == 1);
  CHECK(r.buffers[0].color.size() == 8 * 6);
}

// What capture writes, replay reads: a frame of as many framebuffers as the reader accepts is
// written and reads back with each of them; one more is refused before any file exists.
TEST_CASE("trace: the recorder refuses a frame beyond the reader's framebuffer limit, writing nothing", "[trace]") {
  const std::filesystem::path dir = testing::freshScratchDir("trace_limits");
  const size_t limit = ReadLimits{}.maxTargets;
  for (const size_t count : {limit, limit + 1}) {
    TraceRecorder recorder;
    const std::unique_ptr<PipelineMaker> inner = makePipelineMaker(PipelineKind::Reference);
    const std::unique_ptr<PipelineMaker> maker = recorder.wrap(*inner);
    std::vector<Framebuffer> fbs;
    fbs.reserve(count);
    for (size_t i = 0; i < count; ++i) {
      fbs.emplace_back(1, 1);
      (void)maker->make(fbs.back());
    }
    const std::filesystem::path path = dir / ("frame" + std::to_string(count) + ".srtrace");
    if (count <= limit) {
      recorder.write(path.string());
      CHECK(readTraceFile(path.string()).targets.size() == count);
    } else {
      CHECK_THROWS_WITH(recorder.write(path.string()),
                        Catch::Contains("drew into " + std::to_string(count) + " framebuffers") &&
                            Catch::Contains("at most " + std::to_string(limit)));
      CHECK_FALSE(std::filesystem::exists(path));
    }
  }
}

}  // namespace shadowref::trace
