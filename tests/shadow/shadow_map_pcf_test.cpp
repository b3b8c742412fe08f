// PCF without acne: with receiver-plane depth bias [Isidoro 2006] (ShadowLookup::receiverPlaneBias,
// the default) each tap of a k × k kernel compares the receiver's plane at that tap, so PCF softens
// shadow edges and changes no point that is fully lit — on the shadow-mapped scenes of scenes/,
// under an oblique spot light (a grazing, sloped floor: moiré with a fixed offset) and on the city
// under a sun (gable ends and walls beside their roofs: creases).
//
// "Fully lit", independently of the map's depths: the oracle's shadow ray finds the point lit,
// nearest sampling (pcf 1) lights it, and over the kernel's footprint the light sees the
// receiver's plane: a ray from the light through each footprint texel's centre meets nothing
// before it crosses the point's plane. That is the fraction PCF estimates (the share of the
// footprint the light sees); where a caster's silhouette or a concave crease (a wall standing on
// the lit ground) lies in the footprint, a darker result is PCF's softening, not acne. Convex
// creases (a roof's edge beside a grazing gable end, a hill's facets) stay in the test: there
// the plane runs in front of the neighbouring face.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "shadow/light_shadow.h"
#include "shadow/scene_passes.h"
#include "oracle/oracle.h"
#include "oracle/triangle_bvh.h"
#include "support/scene_oracle.h"

using namespace shadowref;

namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr int kWidth = 160, kHeight = 128;
#else
constexpr int kWidth = 320, kHeight = 256;
#endif

struct PcfCase {
  std::string name, file;
  std::vector<std::string> overrides;
};

Scene load(const PcfCase& c, int pcf, bool receiverPlane = true) {
  std::vector<std::string> overrides = c.overrides;
  overrides.push_back("shadow.pcf=" + std::to_string(pcf));
  overrides.push_back(std::string("shadow.receiver_plane_bias=") + (receiverPlane ? "kernel" : "off"));
  return testing::sceneAtSize(c.file + ".yaml", kWidth, kHeight, overrides);
}

// Every caster's triangles in world space, as the map pass draws them.
oracle::TriangleBvh casterBvh(const std::vector<Instance>& instances, const Light& light) {
  std::vector<oracle::BvhTriangle> triangles;
  for (size_t i = 0; i < instances.size(); ++i) {
    const Instance& inst = instances[i];
    if (!inst.shadowMesh || !withinRange(light, inst.shadowBounds)) continue;
    const Mesh& m = *inst.shadowMesh;
    for (uint32_t k = 0; k < m.triangles.size(); ++k) {
      auto world = [&](uint32_t v) { return glm::dvec3(inst.world * glm::dvec4(m.positions[v], 1.0)); };
      triangles.push_back({world(m.triangles[k].x), world(m.triangles[k].y), world(m.triangles[k].z), int(i), k});
    }
  }
  return oracle::TriangleBvh(std::move(triangles));
}

std::unique_ptr<LightShadow> shadowOf(const Scene& s) { return testing::firstLightShadow(s, s.shadow.method == "tsm"); }

const std::vector<PcfCase>& cases() {
  static const std::vector<PcfCase> all = {
      {"spot", "spot", {}},
      // The spot from the side, 30° above the floor at its centre: a grazing, sloped receiver.
      {"oblique spot", "spot", {"lights.0.position=[5, 3, 2]", "lights.0.direction=[-5, -3, -2]", "lights.0.spot_cutoff=40"}},
      {"city under a sun", "city16_sun", {}},
      {"outdoor (TSM)", "outdoor", {}},
  };
  return all;
}

// The points of a case that nearest sampling and the oracle agree are lit.
struct LitPoints {
  Scene nearest;
  oracle::OracleImage oracle;
  std::vector<glm::dvec4> planes;
  std::vector<size_t> lit;  // pixel indices
  size_t compared = 0;
};

LitPoints litPoints(const PcfCase& c) {
  LitPoints out{load(c, 1), {}, {}, {}, 0};
  const Scene& scene = out.nearest;
  const Light& light = scene.lights.at(0);
  out.oracle = oracle::castOracle(scene, light);
  const oracle::OracleImage& o = out.oracle;
  out.planes = oracle::hitPlanes(o, scene.instances());
  const auto one = shadowOf(scene);
  const double cosCutoff = std::cos(light.spotCutoffDegrees * M_PI / 180.0);
  for (size_t i = 0; i < o.hitPoint.size(); ++i) {
    if (!o.hitMask[i]) continue;
    const glm::dvec3 p = o.hitPoint[i];
    if (light.type == LightType::Spot &&
        glm::dot(glm::normalize(p - light.position), glm::normalize(light.direction)) < cosCutoff)
      continue;
    const glm::dvec4 strq = one->lookup.textureMatrix * glm::dvec4(p, 1.0);
    if (!(strq.w > 0.0)) continue;
    // Outside a map fitted to the casters nothing is looked up (lit, ShadowLookup::outsideLit).
    const double s = strq.x / strq.w, t = strq.y / strq.w;
    if (one->lookup.outsideLit && (s < 0.0 || s > 1.0 || t < 0.0 || t > 1.0)) continue;
    ++out.compared;
    if (o.lit[i] && one->factor(p, out.planes[i]) == 1.0) out.lit.push_back(i);
  }
  return out;
}

// Per lit point, whether the light sees the point's plane through every texel of the k × k
// footprint that `shadow`'s map (k = its pcf) reads around the point: no caster before the plane on
// the ray from the light through each texel's centre (a relative 1e-9 of the ray, about a
// micrometre, for rounding). The footprint is the map's own: a directional map's fit leaves room
// for the kernel, so its texels differ with k.
std::vector<uint8_t> fullyLit(const LitPoints& points, const LightShadow& shadow) {
  const Scene& scene = points.nearest;
  const Light& light = scene.lights.at(0);
  const std::vector<Instance> instances = scene.instances();
  const oracle::TriangleBvh bvh = casterBvh(instances, light);
  const glm::dmat4& T = shadow.lookup.textureMatrix;
  const glm::dmat4 toWorld = glm::inverse(T);
  const int n = shadow.lookup.sampler.texture->width, half = shadow.lookup.pcf / 2;
  // The ray from the light through a texel's centre, and the distance along it (in units of its
  // direction) to the first caster; cached per texel.
  struct Ray {
    bool cast = false;
    glm::dvec3 origin{0.0}, direction{0.0};
    double firstHit = 0.0;  // infinity: none
  };
  std::vector<Ray> rays(size_t(n) * size_t(n));
  auto rayThrough = [&](int x, int y) -> const Ray& {
    Ray& ray = rays[size_t(y) * size_t(n) + size_t(x)];
    if (ray.cast) return ray;
    const double s = (x + 0.5) / n, t = (y + 0.5) / n;
    const glm::dvec4 a = toWorld * glm::dvec4(s, t, 0.0, 1.0), b = toWorld * glm::dvec4(s, t, 1.0, 1.0);
    const glm::dvec3 nearPoint = glm::dvec3(a) / a.w, farPoint = glm::dvec3(b) / b.w;
    // From the spot light itself, or for a sun from far before the map's near plane (a focused
    // TSM depth range clamps casters before it into the map).
    ray.origin = light.type == LightType::Spot ? light.position : nearPoint - (farPoint - nearPoint) * 1e3;
    ray.direction = farPoint - ray.origin;
    const oracle::RayHit hit = bvh.firstHit(ray.origin, ray.direction, 0.0, 1.0);
    ray.firstHit = hit.found() ? hit.t : kInfinity;
    ray.cast = true;
    return ray;
  };
  std::vector<uint8_t> out;
  for (const size_t i : points.lit) {
    const glm::dvec4& plane = points.planes[i];
    const glm::dvec4 strq = T * glm::dvec4(points.oracle.hitPoint[i], 1.0);
    const glm::ivec2 centre(nearestTexel(strq.x / strq.w, n), nearestTexel(strq.y / strq.w, n));
    bool seen = true;
    for (int dy = -half; dy <= half && seen; ++dy)
      for (int dx = -half; dx <= half && seen; ++dx) {
        const int x = centre.x + dx, y = centre.y + dy;
        if (x < 0 || y < 0 || x >= n || y >= n) {  // the sampler clamps there: not the footprint
          seen = false;
          break;
        }
        const Ray& ray = rayThrough(x, y);
        const double along = glm::dot(glm::dvec3(plane), ray.direction);
        const double atPlane = along != 0.0 ? -(glm::dot(glm::dvec3(plane), ray.origin) + plane.w) / along : -kInfinity;
        seen = along != 0.0 && !(ray.firstHit < atPlane * (1.0 - 1e-9));
      }
    out.push_back(seen);
  }
  return out;
}

// Compared points whose factor `shadow` gives differently from nearest sampling (`one`).
size_t changed(const LitPoints& points, const LightShadow& one, const LightShadow& shadow) {
  size_t count = 0;
  const oracle::OracleImage& o = points.oracle;
  for (size_t i = 0; i < o.hitPoint.size(); ++i)
    if (o.hitMask[i] && shadow.factor(o.hitPoint[i], points.planes[i]) != one.factor(o.hitPoint[i], points.planes[i])) ++count;
  return count;
}

// Fully lit points (of `fully`) that a k × k lookup of `shadow` darkens.
size_t darkened(const LitPoints& points, const std::vector<uint8_t>& fully, const LightShadow& shadow) {
  size_t count = 0;
  for (size_t j = 0; j < points.lit.size(); ++j) {
    const size_t i = points.lit[j];
    if (fully[j] && shadow.factor(points.oracle.hitPoint[i], points.planes[i]) != 1.0) ++count;
  }
  return count;
}

}  // namespace

TEST_CASE("PCF 3 and 5 with receiver-plane bias keep every fully lit point lit, and soften the edges",
          "[shadowmap-pcf]") {
  for (const PcfCase& c : cases()) {
    INFO(c.name);
    const LitPoints points = litPoints(c);
    const auto three = shadowOf(load(c, 3));
    const auto five = shadowOf(load(c, 5));
    const std::vector<uint8_t> fully3 = fullyLit(points, *three), fully5 = fullyLit(points, *five);
    size_t full3 = 0, full5 = 0;
    for (size_t j = 0; j < points.lit.size(); ++j) full3 += fully3[j], full5 += fully5[j];
    size_t softened = 0;
    const double fail = points.nearest.shadow.compareFail;
    for (size_t i = 0; i < points.oracle.hitPoint.size(); ++i) {
      if (!points.oracle.hitMask[i]) continue;
      const double f3 = three->factor(points.oracle.hitPoint[i], points.planes[i]);
      if (f3 > fail && f3 < 1.0) ++softened;
    }
    const size_t dark3 = darkened(points, fully3, *three), dark5 = darkened(points, fully5, *five);
    INFO(points.compared << " points compared, " << points.lit.size() << " lit with pcf 1 and by the oracle, " << full3
                         << " / " << full5 << " of them fully lit over the 3 × 3 / 5 × 5 footprint, " << dark3 << " / "
                         << dark5 << " darkened; " << softened << " fractional with pcf 3; "
                         << changed(points, *shadowOf(points.nearest), *three) << " changed by pcf 3");
    CHECK(full5 > points.lit.size() * 3 / 4);  // the test is about most of the lit scene, not a corner of it
    CHECK(dark3 == 0);
    CHECK(dark5 == 0);
    CHECK(softened > 50);  // the edges are softened
  }
}

TEST_CASE("Without receiver-plane bias PCF darkens fully lit points beside the city's creases", "[shadowmap-pcf]") {
  // The polygon offset scaled by the kernel's width (pcfOffsetFactor) covers a receiver's own
  // plane, not a neighbouring face of another slope in the outer taps: the case the bias is for.
  const PcfCase& city = cases().at(2);
  const LitPoints points = litPoints(city);
  const auto three = shadowOf(load(city, 3, false));
  const auto five = shadowOf(load(city, 5, false));
  const size_t dark3 = darkened(points, fullyLit(points, *three), *three);
  const size_t dark5 = darkened(points, fullyLit(points, *five), *five);
  INFO(dark3 << " / " << dark5 << " fully lit points darkened by pcf 3 / 5 without receiver-plane bias; "
             << changed(points, *shadowOf(points.nearest), *three) << " points changed by pcf 3");
  CHECK(dark3 > 0);
  CHECK(dark5 > dark3);
}
