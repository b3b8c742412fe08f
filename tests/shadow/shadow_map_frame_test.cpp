// Shadow-mapped frames ([Hempe 2004, §3.1, §4.1, §4.2, §5]): the whole frame glue of
// shadow_map_renderer.cpp and light_shadow.cpp against hand-computed shadows.
//
// The scene: an 8 × 8 ground slab (top at y = 0) and a 2 × 1 × 2 box hovering at y = 1 … 2. Under
// a directional light straight down the map fitted to the scene box (`fit: scene`) is orthographic
// over x, z ∈ [−4, 4]: with N = 256 a texel is 1/32 wide, and the footprint |x|, |z| < 1 is exactly
// 64 texels. Fitted to the casters (the default) it covers the box's footprint and a margin.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"
#include "shadow/light_shadow.h"
#include "shadow/scene_view.h"
#include "shadow/soft_lights.h"

using namespace shadowref;

namespace {

constexpr double kFail = 0.4;  // [Hempe 2004, §5.1.2]: GL_TEXTURE_COMPARE_FAIL_VALUE

std::string sceneYaml(const std::string& light, const std::string& camera, const std::string& shadow) {
  return "image: {width: 200, height: 160}\n"
         "camera: " + camera + "\n"
         "ambient: 0.2\n"
         "lights:\n  - " + light + "\n"
         "materials:\n  grey: {diffuse: 0.7}\n  red: {diffuse: [0.8, 0.2, 0.1]}\n"
         "meshes:\n  ground: {plane: {size: [8, 8]}}\n  block: {box: {size: [2, 1, 2]}}\n"
         "nodes:\n  - {name: ground, mesh: ground, material: grey}\n"
         "  - {name: block, mesh: block, material: red, translate: [0, 1.5, 0]}\n"
         "shadow: " + shadow + "\n";
}

const std::string kSun = "{name: sun, type: directional, direction: [0, -1, 0]}";
const std::string kObliqueSun = "{name: sun, type: directional, direction: [-1, -1, 0]}";
const std::string kSpot = "{name: spot, type: spot, position: [0, 6, 0], direction: [0, -1, 0], spot_cutoff: 45}";
const std::string kBulb = "{name: bulb, type: point, position: [0, 6, 0]}";
const std::string kCamera = "{eye: [5, 7, 6], target: [0, 0, 0], fov: 50, near: 0.5, far: 40}";

Scene makeScene(const std::string& light, const std::string& shadow = "{method: shadowmap, map_size: 256}",
                const std::string& camera = kCamera) {
  return loadSceneFromString(sceneYaml(light, camera, shadow), "<frame test>");
}

std::unique_ptr<LightShadow> shadowOf(const Scene& scene, bool trapezoidal = false) {
  RasterStats stats;
  Framebuffer frame(1, 1);  // the maps' pipelines are made like this one
  return buildLightShadow(scene, scene.instances(), makeCameraView(scene), scene.lights.at(0), trapezoidal,
                          *makePipeline(PipelineKind::Fast, frame), stats);
}

// Ground points on a 1/64 grid (1/16 under AddressSanitizer, which CI runs too) offset by 1/128,
// so none lies on a texel edge (1/32 steps).
#if defined(__SANITIZE_ADDRESS__)
constexpr double kGridStep = 1.0 / 16;
#else
constexpr double kGridStep = 1.0 / 64;
#endif
std::vector<glm::dvec3> groundGrid(double half) {
  std::vector<glm::dvec3> points;
  for (double x = -half + 1.0 / 128; x < half; x += kGridStep)
    for (double z = -half + 1.0 / 128; z < half; z += kGridStep) points.push_back({x, 0.0, z});
  return points;
}

// Point counts below scale with the grid.
constexpr double kGridScale = (1.0 / 64) * (1.0 / 64) / (kGridStep * kGridStep);

// Within `tolerance` of the square |x|, |z| = edge: the one place a map of finite resolution
// may disagree with the hand-computed shadow.
bool nearSquareEdge(const glm::dvec3& p, double edge, double tolerance) {
  const double m = std::max(std::abs(p.x), std::abs(p.z));
  return std::abs(m - edge) <= tolerance;
}

// The world position of pixel (x, y) from the frame's depth buffer.
glm::dvec3 unproject(const Scene& scene, const Framebuffer& fb, int x, int y) {
  const SceneView view = makeCameraView(scene);
  const double depth = fb.depthCodec().decode(fb.depthCodes()[size_t(y) * size_t(fb.width()) + size_t(x)]);
  const glm::dvec4 ndc((x + 0.5) / fb.width() * 2.0 - 1.0, (y + 0.5) / fb.height() * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
  const glm::dvec4 world = glm::inverse(view.projection * view.view) * ndc;
  return glm::dvec3(world) / world.w;
}

FrameResult render(const Scene& scene, int threads = 1) {
  FrameOptions options;
  options.threads = threads;
  return renderFrame(scene, options);
}

bool sameColour(const Framebuffer& a, const Framebuffer& b) { return a.color() == b.color(); }

}  // namespace

TEST_CASE("shadow map frame: a directional light straight down shadows exactly the box's footprint, to one texel",
          "[shadowmap-frame]") {
  const Scene scene = makeScene(kSun);
  const auto shadow = shadowOf(scene);
  const double texel = 8.0 / 256;
  size_t inside = 0, outside = 0;
  for (const glm::dvec3& p : groundGrid(3.9)) {
    if (nearSquareEdge(p, 1.0, texel)) continue;
    const bool underBox = std::abs(p.x) < 1.0 && std::abs(p.z) < 1.0;
    INFO("ground point " << p.x << ", " << p.z);
    REQUIRE(shadow->factor(p) == (underBox ? kFail : 1.0));
    ++(underBox ? inside : outside);
  }
  CHECK(inside > 10000 * kGridScale);
  CHECK(outside > 100000 * kGridScale);
  // The box's top face is lit; its underside (facing away, in its own shadow) is not.
  CHECK(shadow->factor({0.3, 2.0, -0.2}) == 1.0);
  CHECK(shadow->factor({0.3, 1.0, -0.2}) == kFail);
}

TEST_CASE("shadow map frame: shadowed fragments get the lit colour times the compare-fail value 0.4 (GL_MODULATE), "
          "exactly where the hand-computed footprint lies", "[shadowmap-frame]") {
  const Scene shadowed = makeScene(kSun);
  Scene lit = shadowed;
  lit.shadow.compareFail = 1.0;  // every comparison "passes": the unshadowed colour
  const FrameResult a = render(shadowed), b = render(lit);
  const Framebuffer& fa = a.framebuffer;
  REQUIRE(fa.depthCodes() == b.framebuffer.depthCodes());
  size_t darkened = 0, unchanged = 0;
  for (int y = 0; y < fa.height(); ++y)
    for (int x = 0; x < fa.width(); ++x) {
      const size_t i = size_t(y) * size_t(fa.width()) + size_t(x);
      const glm::vec4 s = fa.color()[i], l = b.framebuffer.color()[i];
      const bool dark = s != l;
      if (dark) {
        ++darkened;
        for (int c = 0; c < 3; ++c) REQUIRE(std::abs(double(s[c]) - kFail * double(l[c])) <= 1e-6 * double(l[c]) + 1e-7);
      } else {
        ++unchanged;
      }
      const glm::dvec3 p = unproject(shadowed, fa, x, y);
      if (std::abs(p.y) > 1e-3 || std::abs(p.x) > 3.9 || std::abs(p.z) > 3.9) continue;  // not the ground top
      if (nearSquareEdge(p, 1.0, 2.0 / 32)) continue;  // one texel, and the depth read-back's rounding
      INFO("pixel " << x << ", " << y << " ground " << p.x << ", " << p.z);
      REQUIRE(dark == (std::abs(p.x) < 1.0 && std::abs(p.z) < 1.0));
    }
  CHECK(darkened > 500);
  CHECK(unchanged > 10000);
}

TEST_CASE("shadow map frame: a Gouraud material is lit per vertex and modulated per fragment (fixed-function "
          "GL_MODULATE): unshadowed, the bytes of the shadowless Gouraud frame, shadowed, 0.4 of them", "[shadowmap-frame]") {
  // The bulb straight above the ground's centre: the slab's top face has only its four corners as
  // vertices, all 8.25 from the light, so per vertex the whole top is one colour, while per pixel
  // it is brightest below the bulb.
  Scene gouraud = makeScene(kBulb);
  for (Material& m : gouraud.materials) m.shading = ShadingModel::Gouraud;
  Scene unshadowed = gouraud;
  unshadowed.shadow.compareFail = 1.0;
  Scene shadowless = gouraud;
  shadowless.shadow.method = "none";
  const Scene perPixel = makeScene(kBulb);
  const FrameResult g = render(gouraud), u = render(unshadowed), none = render(shadowless), pp = render(perPixel);
  REQUIRE(u.framebuffer.color() == none.framebuffer.color());
  REQUIRE(u.framebuffer.depthCodes() == none.framebuffer.depthCodes());
  const Framebuffer& fb = g.framebuffer;
  std::vector<glm::vec4> groundLit, groundPerPixel;
  size_t darkened = 0;
  for (int y = 0; y < fb.height(); ++y)
    for (int x = 0; x < fb.width(); ++x) {
      const size_t i = size_t(y) * size_t(fb.width()) + size_t(x);
      const glm::vec4 s = fb.color()[i], l = none.framebuffer.color()[i];
      if (s != l) {
        ++darkened;
        for (int c = 0; c < 3; ++c) REQUIRE(std::abs(double(s[c]) - kFail * double(l[c])) <= 1e-6 * double(l[c]) + 1e-7);
      }
      const glm::dvec3 p = unproject(gouraud, fb, x, y);
      if (std::abs(p.y) > 1e-3 || std::abs(p.x) > 3.9 || std::abs(p.z) > 3.9 || s != l) continue;  // lit ground top
      groundLit.push_back(s);
      groundPerPixel.push_back(pp.framebuffer.color()[i]);
    }
  CHECK(darkened > 500);
  REQUIRE(groundLit.size() > fb.pixelCount() / 4);  // the lit ground top: most of the view's lower half
  // Hand-computed: the global ambient 0.2 times the material's ambient, 0.2 by default (the
  // material sets only its diffuse colour; docs/scene-format.md), plus diffuse 0.7 · cos at a
  // corner, 6 / sqrt(4² + 6² + 4²).
  const double corner = 0.2 * 0.2 + 0.7 * 6.0 / std::sqrt(68.0);
  for (const glm::vec4& c : groundLit) REQUIRE(c == groundLit.front());
  CHECK(double(groundLit.front().r) == Approx(corner).epsilon(1e-6));
  const auto brightest = std::max_element(groundPerPixel.begin(), groundPerPixel.end(),
                                          [](const glm::vec4& a, const glm::vec4& b) { return a.r < b.r; });
  CHECK(double(brightest->r) > corner + 0.1);  // per pixel: well above the corners' colour
}

TEST_CASE("shadow map frame: under more shadow-mapped lights than the varyings hold, a Gouraud material is lit per "
          "pixel, and the frame says so", "[shadowmap-frame]") {
  std::string lights = kBulb;
  for (int i = 1; i < 5; ++i)
    lights += "\n  - {name: bulb" + std::to_string(i) + ", type: point, position: [" + std::to_string(i - 2.5) + ", 6, 1]}";
  const std::string shadow = "{method: shadowmap, map_size: 64}";
  Scene gouraud = makeScene(lights, shadow);
  REQUIRE(gouraud.lights.size() == 5);
  for (Material& m : gouraud.materials) m.shading = ShadingModel::Gouraud;
  const FrameResult g = render(gouraud), pp = render(makeScene(lights, shadow));
  CHECK(sameColour(g.framebuffer, pp.framebuffer));
  const auto said = std::find_if(g.notes.begin(), g.notes.end(), [](const std::string& n) {
    return n.find("Gouraud materials lit per pixel") != std::string::npos;
  });
  CHECK(said != g.notes.end());
  CHECK(std::none_of(pp.notes.begin(), pp.notes.end(), [](const std::string& n) { return n.find("Gouraud") != std::string::npos; }));
}

TEST_CASE("shadow map frame: a spot light above the box throws the top face's projection, scaled 6/4", "[shadowmap-frame]") {
  const Scene scene = makeScene(kSpot);
  const auto shadow = shadowOf(scene);
  // Light at height 6, box top at 2: the silhouette |x|, |z| < 1 projects to |x|, |z| < 1.5.
  // The map spans the 90° cone: 12 m at the ground over 256 texels.
  const double texel = 12.0 / 256;
  size_t inside = 0;
  for (const glm::dvec3& p : groundGrid(3.9)) {
    if (nearSquareEdge(p, 1.5, 1.5 * texel)) continue;
    const bool shadowed = std::abs(p.x) < 1.5 && std::abs(p.z) < 1.5;
    INFO("ground point " << p.x << ", " << p.z);
    REQUIRE(shadow->factor(p) == (shadowed ? kFail : 1.0));
    inside += shadowed;
  }
  CHECK(inside > 30000 * kGridScale);
}

TEST_CASE("shadow map frame: a point light's cube maps shadow the ground as the spot map of the same frustum does",
          "[shadowmap-frame]") {
  // The cube's −Y face is a 90° perspective view straight down with up −z: the spot light with
  // cutoff 45° looking down has the same view (light_view.h), only near and far differ.
  const auto cube = shadowOf(makeScene(kBulb));
  const auto spot = shadowOf(makeScene(kSpot));
  REQUIRE(cube->cube);
  size_t compared = 0, shadowed = 0;
  for (const glm::dvec3& p : groundGrid(3.9)) {
    if (cubeFaceFor(p - glm::dvec3(0, 6, 0)) != CubeFace::NegativeY) continue;
    INFO("ground point " << p.x << ", " << p.z);
    REQUIRE(cube->factor(p) == spot->factor(p));
    ++compared;
    shadowed += cube->factor(p) < 1.0;
  }
  CHECK(compared > 100000 * kGridScale);
  CHECK(shadowed > 30000 * kGridScale);
  // The +Y face sees the box's top from below the light: lit. A point beside the box, on the
  // +X face, behind nothing: lit.
  CHECK(cube->factor({0.2, 2.0, 0.1}) == 1.0);
  CHECK(cube->factor({3.5, 0.0, 0.0}) == 1.0);
}

TEST_CASE("shadow map frame: TSM equals standard mapping when the trapezoid is the whole light view (fallback, N_T = I)",
          "[shadowmap-frame]") {
  // The camera looks straight down along the light from high above and sees the whole scene:
  // the degenerate case of [Hempe 2004, Listing 10e], whose bounding rectangle is the light's whole
  // view.
  const std::string camera = "{eye: [0, 30, 0], target: [0, 0, 0], up: [0, 0, -1], fov: 40, near: 1, far: 60}";
  const Scene standard = makeScene(kSun, "{method: shadowmap, map_size: 256, fit: scene}", camera);
  const Scene trapezoidal = makeScene(kSun, "{method: tsm, map_size: 256}", camera);
  const auto tsm = shadowOf(trapezoidal, true);
  REQUIRE(tsm->trapezoidal);
  REQUIRE(tsm->trapezoid.fallback);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) CHECK(tsm->trapezoid.NT[c][r] == Approx(c == r ? 1.0 : 0.0).margin(1e-12));
  CHECK(tsm->textures[0].bits == shadowOf(standard)->textures[0].bits);
  CHECK(sameColour(render(standard).framebuffer, render(trapezoidal).framebuffer));
}

TEST_CASE("shadow map frame: TSM shadows the hand-computed footprint too, seen from an oblique camera",
          "[shadowmap-frame]") {
  const Scene scene = makeScene(kSun, "{method: tsm, map_size: 256}");
  const auto shadow = shadowOf(scene, true);
  REQUIRE_FALSE(shadow->trapezoid.fallback);
  // The warped map's texels vary in size; nowhere on this ground are they above 2/32.
  for (const glm::dvec3& p : groundGrid(3.9)) {
    if (nearSquareEdge(p, 1.0, 2.0 / 32)) continue;
    INFO("ground point " << p.x << ", " << p.z);
    REQUIRE(shadow->factor(p) == (std::abs(p.x) < 1.0 && std::abs(p.z) < 1.0 ? kFail : 1.0));
  }
}

TEST_CASE("shadow map frame: polygon offset, constant bias and back faces only each keep an oblique sun's lit ground lit, "
          "without any, the ground shadows itself", "[shadowmap-frame]") {
  // Sun along (−1, −1, 0): the box (y 1 … 2) shadows x ∈ [−3, 0], |z| < 1.
  const std::vector<std::string> choices = {
      "{method: shadowmap, map_size: 256}",  // offset 1.1, 4 (the default)
      "{method: shadowmap, map_size: 256, offset_factor: 0, offset_units: 0, bias: 0.005}",
      "{method: shadowmap, map_size: 256, offset_factor: 0, offset_units: 0, back_faces_only: true}",
      "{method: tsm, map_size: 256}"};
  for (const std::string& choice : choices) {
    const Scene scene = makeScene(kObliqueSun, choice);
    const auto shadow = shadowOf(scene, scene.shadow.method == "tsm");
    INFO("shadow settings " << choice);
    for (const glm::dvec3& p : groundGrid(3.8)) {
      const bool clearlyLit = p.x > 0.2 || std::abs(p.z) > 1.2 || p.x < -3.2;
      const bool clearlyShadowed = p.x > -2.8 && p.x < -0.2 && std::abs(p.z) < 0.8;
      if (clearlyLit) REQUIRE(shadow->factor(p) == 1.0);
      if (clearlyShadowed) REQUIRE(shadow->factor(p) == kFail);
    }
  }
  const auto bare = shadowOf(makeScene(kObliqueSun, "{method: shadowmap, map_size: 256, offset_factor: 0, offset_units: 0}"));
  size_t acne = 0;
  for (const glm::dvec3& p : groundGrid(3.8))
    if (p.x > 0.2 && bare->factor(p) < 1.0) ++acne;
  CHECK(acne > 1000 * kGridScale);
}

TEST_CASE("shadow map frame: 3x3 PCF blends the compare results at the shadow's edge and leaves the inside alone",
          "[shadowmap-frame]") {
  const auto pcf = shadowOf(makeScene(kSun, "{method: shadowmap, map_size: 256, pcf: 3, fit: scene}"));
  const double texel = 8.0 / 256;
  CHECK(pcf->factor({0.0, 0.0, 0.0}) == Approx(kFail).epsilon(1e-12));  // the mean of nine 0.4s
  CHECK(pcf->factor({2.5, 0.0, 2.5}) == 1.0);
  // Half a texel inside the edge x = 1: the 3 x 3 block holds 2 columns inside, 1 outside:
  // 6 comparisons fail, 3 pass.
  CHECK(pcf->factor({1.0 - 0.5 * texel, 0.0, 0.0}) == Approx((6 * kFail + 3 * 1.0) / 9).epsilon(1e-12));
  CHECK(pcf->factor({1.0 + 0.5 * texel, 0.0, 0.0}) == Approx((3 * kFail + 6 * 1.0) / 9).epsilon(1e-12));
  // The corner: 4 of 9 inside.
  CHECK(pcf->factor({1.0 - 0.5 * texel, 0.0, 1.0 - 0.5 * texel}) == Approx((4 * kFail + 5 * 1.0) / 9).epsilon(1e-12));
}

TEST_CASE("shadow map frame: the 16-light accumulation ([Hempe 2004, §4.2]) equals the average of 16 separately rendered frames",
          "[shadowmap-frame]") {
  const std::string area = "{name: spot, type: spot, position: [0, 6, 0], direction: [0, -1, 0], spot_cutoff: 45, "
                           "soft: {shape: area16, spacing: 1}}";
  for (const char* method : {"shadowmap", "tsm"}) {
    INFO("method " << method);
    const Scene soft = makeScene(area, std::string("{method: ") + method + ", map_size: 256}");
    const std::vector<Light> positions = expandSoftLight(soft.lights.at(0));
    REQUIRE(positions.size() == 16);
    std::vector<glm::vec4> sum(size_t(soft.width) * size_t(soft.height), glm::vec4(0.0f));
    std::vector<PixelVector<glm::vec4>> singles;
    for (const Light& position : positions) {
      Scene one = soft;
      one.lights = {position};
      one.lights[0].soft = SoftShape::None;
      one.lights[0].color = soft.lights[0].color;  // every frame is a whole picture, weighted 1/16
      singles.push_back(render(one).framebuffer.color());
    }
    // The accumulation buffer's arithmetic: LOAD then ACCUM with the float weight 1/16.
    for (size_t k = 0; k < singles.size(); ++k)
      for (size_t i = 0; i < sum.size(); ++i) sum[i] += singles[k][i] * (1.0f / 16.0f);
    const PixelVector<glm::vec4> accumulated = render(soft).framebuffer.color();
    double worst = 0.0;
    for (size_t i = 0; i < sum.size(); ++i)
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(accumulated[i][c]) - double(sum[i][c])));
    CHECK(worst <= 1e-6);
    // Not vacuous: the 16 lights throw different shadows, so the penumbra has in-between values.
    CHECK(singles[0] != singles[8]);
  }
}

TEST_CASE("shadow map frame: every method gives the same bytes on every run and with any thread count",
          "[shadowmap-frame]") {
  const std::string area = "{name: spot, type: spot, position: [0, 6, 0], direction: [0, -1, 0], spot_cutoff: 45, "
                           "soft: {shape: area16, spacing: 0.5}}";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {kObliqueSun, "{method: shadowmap, map_size: 256, pcf: 3}"},
      {kObliqueSun, "{method: tsm, map_size: 256}"},
      {kBulb, "{method: shadowmap, map_size: 128}"},
      {area, "{method: tsm, map_size: 128}"}};
  for (const auto& [light, shadow] : cases) {
    INFO(light << " " << shadow);
    const Scene scene = makeScene(light, shadow);
    const FrameResult a = render(scene, 1), b = render(scene, 1), c = render(scene, 3);
    CHECK(sameColour(a.framebuffer, b.framebuffer));
    CHECK(sameColour(a.framebuffer, c.framebuffer));
    CHECK(a.framebuffer.depthCodes() == c.framebuffer.depthCodes());
  }
}
