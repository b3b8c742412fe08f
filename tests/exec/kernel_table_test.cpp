// The dispatch table of the span kernels (FragmentProcessor::kernelTable): for each row, a draw
// state meeting its condition takes that row, and the row's kernel leaves the bytes and counters
// that the reference function it names leaves when called at every covered pixel (gl/coverage.h)
// of the same triangles over the same buffers.
#include <cstring>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "exec/fragment_processor.h"
#include "gl/coverage.h"
#include "gl/per_fragment.h"
#include "gl/primitive_assembly.h"
#include "support/raster_harness.h"

using namespace shadowref;
using namespace shadowref::testing;

namespace {

constexpr int kWidth = 53, kHeight = 37;  // odd sizes: rows end inside a step of eight

// A state meeting the condition of the table's row `name`, and its shader (nullptr: none).
struct KernelCase {
  const char* name;
  RenderState state;
  const FragmentShader* shader;
};

std::vector<KernelCase> kernelCases(const Framebuffer& fb, const FragmentShader& varying,
                                    const FragmentShader& constant) {
  std::vector<KernelCase> cases;
  RenderState volume = fullViewportState(fb);  // a z-fail volume pass
  volume.depthTest = true;
  volume.depthFunc = CompareFunc::Less;
  volume.depthWrite = false;
  volume.colorMask = {false, false, false, false};
  volume.stencilTest = true;
  volume.stencil[FrontFacing].dpfail = StencilOp::DecrWrap;
  volume.stencil[BackFacing].dpfail = StencilOp::IncrWrap;
  cases.push_back({"countTriangle", volume, nullptr});

  RenderState map = fullViewportState(fb);  // a shadow map
  map.depthTest = true;
  map.depthFunc = CompareFunc::LEqual;
  map.colorMask = {false, false, false, false};
  map.polygonOffset = {true, 1.5, 2.0};
  cases.push_back({"depthTriangle", map, nullptr});

  RenderState ambient = fullViewportState(fb);  // the ambient pass
  ambient.depthTest = true;
  ambient.depthFunc = CompareFunc::Less;
  cases.push_back({"constantColorTriangle", ambient, &constant});

  RenderState lit = fullViewportState(fb);  // a lit pass: the stencil filters, colours add
  lit.depthTest = true;
  lit.depthFunc = CompareFunc::LEqual;
  lit.stencilTest = true;
  for (StencilFaceState& f : lit.stencil) {
    f.func = CompareFunc::Equal;
    f.ref = 1;
    f.dppass = StencilOp::Replace;
  }
  lit.blend = {true, BlendFactor::One, BlendFactor::One};
  cases.push_back({"spanTriangle", lit, &varying});
  return cases;
}

// Random triangles over the buffer and beyond its edges, with perspective and varyings.
std::vector<ClipVertex> randomTriangles(TestRandom& r, const Viewport& vp, int count) {
  std::vector<ClipVertex> out;
  for (int i = 0; i < count; ++i) {
    const double cx = r.uniform(-5.0, vp.width + 5.0), cy = r.uniform(-5.0, vp.height + 5.0);
    const double size = r.uniform(2.0, 40.0);
    for (int k = 0; k < 3; ++k) {
      ClipVertex v = windowVertex(vp, cx + r.uniform(-size, size), cy + r.uniform(-size, size), r.uniform(0.0, 1.0));
      v.position *= r.uniform(0.5, 3.0);
      for (int c = 0; c < 4; ++c) v.varyings[size_t(c)] = r.uniform(0.0, 1.0);
      out.push_back(v);
    }
  }
  return out;
}

// The buffers the state needs, filled with the same random contents for every seed: stencil bytes
// 0..2 (the lit pass's test passes and fails), depths across [0, 1], colours.
void fillBuffers(Framebuffer& fb, const DrawCall& call, uint64_t seed) {
  ensureBuffersFor(fb, call);
  TestRandom r(seed);
  if (fb.hasStencil())
    for (uint8_t& s : fb.stencil()) s = uint8_t(r.below(3));
  if (fb.hasDepth())
    for (uint32_t& d : fb.depthCodes()) d = fb.depthCodec().encode(r.uniform());
  if (fb.hasColor())
    for (glm::vec4& c : fb.color()) c = glm::vec4(float(r.uniform()), float(r.uniform()), float(r.uniform()), 1.0f);
}

template <class T>
bool sameBytes(const PixelVector<T>& a, const PixelVector<T>& b) {
  return a.size() == b.size() && (a.size() == 0 || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

}  // namespace

TEST_CASE("every row of the kernel table reproduces the reference function it names", "[exec][kernels]") {
  const ColorVaryingShader varying;
  const ConstantColorShader constant({0.25, 0.5, 0.75, 1.0});
  const Framebuffer sizing(kWidth, kHeight);
  const std::vector<KernelCase> cases = kernelCases(sizing, varying, constant);
  const auto table = FragmentProcessor::kernelTable();
  REQUIRE(table.size() == cases.size());  // a case for every row
  for (size_t row = 0; row < table.size(); ++row) {
    const FragmentProcessor::KernelEntry& entry = table[row];
    const KernelCase& c = cases[row];
    INFO("row " << row << ": " << entry.name << " (" << entry.condition << ")");
    REQUIRE(std::string(entry.name) == c.name);
    // The named reference is the function the one-fragment path calls, the reference pipeline's.
    CHECK(std::string(entry.reproduces) == "processFragment");
    CHECK(entry.reference == &processFragment);
    CHECK(entry.reference == FragmentProcessor::kDefinition);
    for (const DepthFormat format : {DepthFormat::Float32, DepthFormat::Unorm24}) {
      for (uint64_t seed = 1; seed <= 4; ++seed) {
        Framebuffer kernelFb(kWidth, kHeight, format), referenceFb(kWidth, kHeight, format);
        TestRandom r(seed * 7919);
        const std::vector<ClipVertex> vertices = randomTriangles(r, c.state.viewport, 24);
        DrawCall call;
        call.state = &c.state;
        call.vertices = vertices;
        call.shader = c.shader;
        fillBuffers(kernelFb, call, seed);
        fillBuffers(referenceFb, call, seed);

        const ClipPlanes planes = clipPlanesFor(c.state);
        const int varyingCount = c.shader ? c.shader->varyingCount() : 0;
        const Rect region = drawRegion(c.state, kernelFb);
        const BufferUse use = bufferUse(referenceFb, c.state, c.shader);
        RasterStats kernelStats, referenceStats, assembly;
        SpanScratch scratch;
        FragmentProcessor kernel(kernelFb, c.state, c.shader, kernelStats, nullptr, scratch);
        REQUIRE(&kernel.kernel() == &entry);  // the state takes this row
        AssemblyScratch assemblyScratch;
        std::vector<TriangleSetup> setups;
        std::vector<CoveredPixel> covered;
        size_t drawn = 0;
        for (size_t i = 0; i + 2 < vertices.size(); i += 3) {
          assembleTriangle(&vertices[i], &vertices[i + 1], &vertices[i + 2], c.state, planes, varyingCount,
                           kernelFb.depthCodec(), assemblyScratch, setups, assembly);
          for (const TriangleSetup& t : setups) {
            kernel.processTriangle(t, region);
            coveredPixels(t, region, covered);
            for (const CoveredPixel& p : covered)
              entry.reference(referenceFb, c.state, c.shader, use, t, p, referenceStats, nullptr);
            drawn += covered.size();
          }
        }
        CHECK(drawn > 500);  // the triangles reached the buffer
        CHECK(sameBytes(kernelFb.color(), referenceFb.color()));
        CHECK(sameBytes(kernelFb.depthCodes(), referenceFb.depthCodes()));
        CHECK(sameBytes(kernelFb.stencil(), referenceFb.stencil()));
        CHECK(kernelStats.fragments == referenceStats.fragments);
        CHECK(kernelStats.stencilFailed == referenceStats.stencilFailed);
        CHECK(kernelStats.depthFailed == referenceStats.depthFailed);
        CHECK(kernelStats.stencilWrites == referenceStats.stencilWrites);
        CHECK(kernelStats.colorWrites == referenceStats.colorWrites);
      }
    }
  }
}

TEST_CASE("a state meeting no special row takes the last, general one", "[exec][kernels]") {
  Framebuffer fb(8, 8);
  fb.ensureStencil();
  RenderState s = fullViewportState(fb);
  s.stencilTest = true;
  s.stencil[FrontFacing].dppass = StencilOp::Replace;  // not a modulo-256 count
  s.colorMask = {false, false, false, false};
  const auto table = FragmentProcessor::kernelTable();
  CHECK(&FragmentProcessor::kernelFor(drawTraits(fb, s, nullptr)) == &table.back());
  s.stencil[FrontFacing].dppass = StencilOp::IncrWrap;  // now it is one
  CHECK(std::string(FragmentProcessor::kernelFor(drawTraits(fb, s, nullptr)).name) == "countTriangle");
}
