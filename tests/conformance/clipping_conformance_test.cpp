// Near-plane clipping and points at infinity (w = 0 in eye space) under the infinite projection
// P_inf ([Kuhn 2016, §3.3]), built on the CPU so both implementations get the same clip
// coordinates.
#include "conformance/case_builder.h"

#include "gl/projection.h"

using namespace shadowref;
using namespace shadowref::conformance;

namespace {

constexpr int kSize = 64;

void addEyeTriangle(DrawStep& d, const glm::dmat4& projection, const glm::dvec4& a, const glm::dvec4& b,
                    const glm::dvec4& c, const glm::dvec4& color) {
  d.vertices.push_back({projection * a, color});
  d.vertices.push_back({projection * b, glm::dvec4(1.0) - color + glm::dvec4(0, 0, 0, 1)});
  d.vertices.push_back({projection * c, color * 0.5});
}

}  // namespace

TEST_CASE("triangles crossing the near plane and reaching points at infinity clip as in Mesa under P_inf",
          "[conformance][clipping]") {
  const glm::dmat4 pinf = infinitePerspective(60.0, 1.0, 0.5);
  Scenario sc;
  sc.name = "P_inf: near-plane crossings, w = 0 vertices, far plane off";
  sc.width = sc.height = kSize;
  DrawStep d;
  d.state = fullViewportState(kSize, kSize);
  d.state.clipFar = false;  // GL clips at z = w, which P_inf never crosses: the same result
  d.state.depthTest = true;
  d.state.depthFunc = CompareFunc::LEqual;
  d.state.stencilTest = true;
  for (StencilFaceState& s : d.state.stencil) s.dppass = StencilOp::IncrWrap;
  // Crossing the near plane (z_eye = -0.5), one vertex behind the eye.
  addEyeTriangle(d, pinf, {-1.0, -0.8, -3.0, 1}, {1.2, -0.5, -2.0, 1}, {0.2, 0.9, 1.5, 1}, {1, 0, 0, 1});
  addEyeTriangle(d, pinf, {-0.7, 0.6, -0.2, 1}, {0.9, 0.3, -4.0, 1}, {-0.4, -0.9, -1.0, 1}, {0, 1, 0, 1});
  // A shadow volume's extruded quad: two vertices at infinity (w = 0) away from the eye.
  addEyeTriangle(d, pinf, {-0.5, -0.5, -2.0, 1}, {0.5, -0.3, -2.5, 1}, {0.3, -0.1, -1.0, 0}, {0, 0, 1, 1});
  addEyeTriangle(d, pinf, {0.5, -0.3, -2.5, 1}, {0.6, -0.05, -1.0, 0}, {0.3, -0.1, -1.0, 0}, {1, 1, 0, 1});
  // A point at infinity behind the eye (w_clip < 0): only the part in front survives.
  addEyeTriangle(d, pinf, {-0.6, 0.2, -1.5, 1}, {0.7, 0.5, -1.8, 1}, {0.1, -0.2, 1.0, 0}, {0, 1, 1, 1});
  // Entirely behind the eye: nothing.
  addEyeTriangle(d, pinf, {-1, -1, 2, 1}, {1, -1, 2, 1}, {0, 1, 3, 1}, {1, 0, 1, 1});
  sc.steps.push_back(d);
  checkAgreement(runCase(sc));
}

TEST_CASE("with depth clamp under P_inf, geometry behind the near plane is kept and clamped as in Mesa",
          "[conformance][clipping][clamp]") {
  const glm::dmat4 pinf = infinitePerspective(60.0, 1.0, 0.5);
  Scenario sc;
  sc.name = "P_inf with depth clamp: near-plane crossings";
  sc.width = sc.height = kSize;
  // The window-space depth gradient is steep here (w down to 0.2); Mesa sets the plane up and
  // evaluates it in float, shadowref in double from the same vertices (docs/conformance.md).
  sc.depthTolerance = 4;
  sc.note = "steep depth near the eye: Mesa's float plane evaluation";
  DrawStep d;
  d.state = fullViewportState(kSize, kSize);
  d.state.depthClamp = true;
  d.state.depthTest = true;
  d.state.depthFunc = CompareFunc::LEqual;
  // In front of the eye but partly nearer than the near plane (z_eye in (-0.5, 0)).
  addEyeTriangle(d, pinf, {-0.3, -0.3, -0.3, 1}, {0.4, -0.2, -2.0, 1}, {0.0, 0.4, -0.25, 1}, {1, 0, 0, 1});
  addEyeTriangle(d, pinf, {-0.6, 0.2, -1.5, 1}, {0.7, 0.5, -1.8, 1}, {0.1, -0.2, -0.2, 1}, {0, 1, 0, 1});
  sc.steps.push_back(d);
  checkAgreement(runCase(sc));
}
