#include "sweep/soft_reference.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <thread>

#include "oracle/triangle_bvh.h"
#include "oracle/world_volumes.h"

namespace shadowref::sweep {

namespace {

glm::dvec3 toWorld(const glm::dmat4& world, const glm::dvec3& p) {
  const glm::dvec4 h = world * glm::dvec4(p, 1.0);
  return glm::dvec3(h) / h.w;
}

// The shadow-casting triangles in world space, and the scene's size for the ray offset — the same
// gathering as the oracle's (src/oracle/oracle.cpp), which keeps it private.
struct Casters {
  oracle::TriangleBvh bvh;
  double scale = 1.0;
};

Casters gatherCasters(const Scene& scene, const Light& light) {
  std::vector<oracle::BvhTriangle> triangles;
  const std::vector<Instance> instances = scene.instances();
  Aabb all;
  all.add(scene.camera.eye);
  for (size_t i = 0; i < instances.size(); ++i) {
    const Instance& inst = instances[i];
    if (!inst.worldBounds.empty()) {
      all.add(inst.worldBounds.min);
      all.add(inst.worldBounds.max);
    }
    if (!oracle::castsShadowFor(inst, light, true)) continue;
    const Mesh& mesh = *inst.shadowMesh;
    std::vector<glm::dvec3> p;
    p.reserve(mesh.positions.size());
    for (const glm::dvec3& v : mesh.positions) p.push_back(toWorld(inst.world, v));
    for (uint32_t t = 0; t < mesh.triangles.size(); ++t) {
      const glm::uvec3 k = mesh.triangles[t];
      triangles.push_back(oracle::BvhTriangle{p[k[0]], p[k[1]], p[k[2]], static_cast<int>(i), t});
    }
  }
  Casters c;
  c.bvh = oracle::TriangleBvh(std::move(triangles));
  c.scale = std::max(1.0, glm::length(all.max - all.min));
  return c;
}

// The oracle's shadow-ray rule for a point light at `q`: the open segment from the hit to q.
bool sees(const Casters& c, const glm::dvec3& p, const glm::dvec3& q) {
  const glm::dvec3 toLight = q - p;
  const double tMin = 1e-7 * c.scale / std::max(glm::length(toLight), 1e-300);
  return !c.bvh.anyHit(p, toLight, tMin, 1.0 - tMin);
}

}  // namespace

std::vector<glm::dvec3> areaLightSamples(Reference shape, const glm::dvec3& centre, double s, int samples) {
  std::vector<glm::dvec3> out;
  if (shape == Reference::AreaSquare) {
    const int n = std::max(1, static_cast<int>(std::lround(std::sqrt(double(samples)))));
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        out.push_back(centre + glm::dvec3(-s + 2.0 * s * (i + 0.5) / n, 0.0, -s + 2.0 * s * (j + 0.5) / n));
  } else if (shape == Reference::AreaSphere) {
    // Fibonacci spiral: equal-area bands in z, golden-angle steps around.
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int k = 0; k < samples; ++k) {
      const double z = 1.0 - 2.0 * (k + 0.5) / samples;
      const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
      out.push_back(centre + s * glm::dvec3(r * std::cos(golden * k), z, r * std::sin(golden * k)));
    }
  } else {
    out.push_back(centre);
  }
  return out;
}

std::vector<float> areaLightVisibility(const Scene& scene, const Light& light, const std::vector<glm::dvec3>& samples,
                                       const oracle::OracleImage& primary, int threads) {
  const Casters casters = gatherCasters(scene, light);
  std::vector<float> visibility(primary.lit.size(), 0.0f);
  auto rows = [&](int first, int step) {
    for (int y = first; y < primary.height; y += step)
      for (int x = 0; x < primary.width; ++x) {
        const size_t i = primary.index(x, y);
        if (!primary.hitMask[i]) continue;
        int seen = 0;
        for (const glm::dvec3& q : samples) seen += sees(casters, primary.hitPoint[i], q);
        visibility[i] = static_cast<float>(double(seen) / double(samples.size()));
      }
  };
  const int n = std::clamp(threads, 1, std::max(1, primary.height));
  std::vector<std::thread> pool;
  for (int t = 1; t < n; ++t) pool.emplace_back(rows, t, n);
  rows(0, n);
  for (std::thread& t : pool) t.join();
  return visibility;
}

}  // namespace shadowref::sweep
