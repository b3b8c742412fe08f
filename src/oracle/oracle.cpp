#include "oracle/oracle.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include "shadow/scene_view.h"
#include "shadow/shadow_lookup.h"
#include "oracle/camera_model.h"
#include "oracle/edge_marks.h"
#include "oracle/screen_bins.h"
#include "oracle/triangle_bvh.h"
#include "oracle/world_volumes.h"

namespace shadowref::oracle {

namespace {

glm::dvec3 toWorld(const glm::dmat4& world, const glm::dvec3& p) {
  const glm::dvec4 h = world * glm::dvec4(p, 1.0);
  return glm::dvec3(h) / h.w;
}

// The mesh's triangles in world space, wound counter-clockwise seen from their outside there (a
// mirroring world matrix reverses the winding; the renderer flips its front face for it).
// `backCulled`: as the scene pass draws them, for the primary rays.
void appendTriangles(const Mesh& mesh, const glm::dmat4& world, int instance, bool backCulled,
                     std::vector<BvhTriangle>& out) {
  std::vector<glm::dvec3> p;
  p.reserve(mesh.positions.size());
  for (const glm::dvec3& v : mesh.positions) p.push_back(toWorld(world, v));
  const bool mirrored = glm::determinant(world) < 0.0;
  for (uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3 i = mesh.triangles[t];
    out.push_back(BvhTriangle{p[i[0]], p[i[mirrored ? 2 : 1]], p[i[mirrored ? 1 : 2]], instance, t, backCulled});
  }
}

struct SceneGeometry {
  std::vector<Instance> instances;
  TriangleBvh visible;   // every instance's render mesh: primary rays
  TriangleBvh casters;   // shadowMesh of the instances casting for the light: shadow rays
  double scale = 1.0;    // size of the scene and camera, for offsets
};

SceneGeometry gatherGeometry(const Scene& scene, const Light& light, const OracleOptions& options) {
  SceneGeometry g;
  g.instances = scene.instances();
  std::vector<BvhTriangle> visible, casters;
  Aabb all;
  all.add(scene.camera.eye);
  for (size_t i = 0; i < g.instances.size(); ++i) {
    const Instance& inst = g.instances[i];
    appendTriangles(*inst.mesh, inst.world, static_cast<int>(i), true, visible);
    if (castsShadowFor(inst, light, options.respectRange))
      appendTriangles(*inst.shadowMesh, inst.world, static_cast<int>(i), false, casters);
    if (!inst.worldBounds.empty()) {
      all.add(inst.worldBounds.min);
      all.add(inst.worldBounds.max);
    }
  }
  g.visible = TriangleBvh(std::move(visible));
  g.casters = TriangleBvh(std::move(casters));
  g.scale = std::max(1.0, glm::length(all.max - all.min));
  return g;
}

// Shadow ray from the hit to the light (point: the segment; directional: the ray towards it).
bool lightVisible(const SceneGeometry& g, const Light& light, const glm::dvec3& p) {
  const glm::dvec4 l = light.homogeneous();
  if (l.w == 0.0) {
    const glm::dvec3 dir = glm::normalize(glm::dvec3(l));
    return !g.casters.anyHit(p, dir, 1e-7 * g.scale, HUGE_VAL);
  }
  const glm::dvec3 toLight = glm::dvec3(l) - p;
  const double tMin = 1e-7 * g.scale / std::max(glm::length(toLight), 1e-300);
  return !g.casters.anyHit(p, toLight, tMin, 1.0 - tMin);
}

struct PixelResult {
  int zpass = 0, zfail = 0;
  bool ambiguous = false;
};

// The signed crossings of one pixel ray, split at the hit (see oracle.h).
PixelResult countCrossings(const WorldVolumes& volumes, const std::vector<uint32_t>& candidates, const PixelRay& ray,
                           const RayHit& hit, const OracleOptions& options) {
  PixelResult r;
  const ProjectiveSegment segment = makeRayToInfinity(ray.origin, ray.direction, ray.tNear);
  const double tHit = hit.found() ? hit.t : HUGE_VAL;
  for (uint32_t index : candidates) {
    const VolumeTriangle& v = volumes.triangles[index];
    const Crossing c = crossSegment(v.triangle, segment);
    if (!c.hit) continue;
    // crossSegment says "entering" by the raw plane; the volume's outside may be the other side.
    const bool front = (v.orientation > 0.0) == c.entering;
    const double t = rayParameter(c, ray.tNear);
    const bool close = std::isfinite(tHit) && std::abs(t - tHit) <= options.depthAmbiguity * tHit;
    bool behind = t >= tHit;
    if (close) {
      // The hit surface's own front cap: same instance, same depth; the rasterizer's LESS fails on it.
      if (v.part == VolumePart::FrontCap && v.instance == hit.instance) behind = true;
      else r.ambiguous = true;
    }
    if (behind) r.zfail += front ? -1 : 1;
    else if (v.countedByZPass) r.zpass += front ? 1 : -1;
  }
  return r;
}

void markGeometryContours(const SceneGeometry& g, const CameraModel& camera, double radius, std::vector<uint8_t>& marks) {
  for (const Instance& inst : g.instances) {
    const Mesh& mesh = *inst.mesh;
    std::vector<glm::dvec3> p;
    for (const glm::dvec3& v : mesh.weldedPositions) p.push_back(toWorld(inst.world, v));
    auto facesEye = [&](uint32_t t) {
      const glm::uvec3 i = mesh.weldedTriangles[t];
      return glm::dot(glm::cross(p[i[1]] - p[i[0]], p[i[2]] - p[i[0]]), camera.eye - p[i[0]]) > 0.0;
    };
    for (const Edge& e : mesh.edges) {
      const bool contour = e.triangleCount != 2 || e.t1 == kNoTriangle || facesEye(e.t0) != facesEye(e.t1);
      if (contour) markNearSegment(camera, glm::dvec4(p[e.v0], 1.0), glm::dvec4(p[e.v1], 1.0), radius, marks);
    }
    if (mesh.edges.empty()) {
      // No adjacency was built: every triangle edge may be a contour.
      for (const glm::uvec3& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
          const glm::dvec3 a = toWorld(inst.world, mesh.positions[t[k]]);
          const glm::dvec3 b = toWorld(inst.world, mesh.positions[t[(k + 1) % 3]]);
          markNearSegment(camera, glm::dvec4(a, 1.0), glm::dvec4(b, 1.0), radius, marks);
        }
    }
  }
}

void markNeighbourChanges(OracleImage& img) {
  std::vector<uint8_t> marks = img.nearEdge;
  auto differs = [&](size_t a, size_t b) {
    return img.hitInstance[a] != img.hitInstance[b] || img.zpass[a] != img.zpass[b] || img.zfail[a] != img.zfail[b];
  };
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const size_t i = img.index(x, y);
      if ((x > 0 && differs(i, i - 1)) || (x + 1 < img.width && differs(i, i + 1)) ||
          (y > 0 && differs(i, i - img.width)) || (y + 1 < img.height && differs(i, i + img.width)))
        marks[i] = 1;
    }
  img.nearEdge.swap(marks);
}

}  // namespace

OracleImage castOracle(const Scene& scene, const Light& light, const OracleOptions& options) {
  const SceneGeometry geometry = gatherGeometry(scene, light, options);
  const CameraModel camera = makeCameraModel(makeCameraView(scene, options.forceInfiniteProjection));
  const WorldVolumes volumes =
      buildWorldVolumes(geometry.instances, light, scene.shadow.silhouette, options.respectRange);
  const ScreenBins bins(camera, volumes);

  OracleImage img;
  img.width = camera.viewport.width;
  img.height = camera.viewport.height;
  const size_t n = static_cast<size_t>(img.width) * img.height;
  img.zpass.assign(n, 0);
  img.zfail.assign(n, 0);
  img.lit.assign(n, 0);
  img.hitMask.assign(n, 0);
  img.nearEdge.assign(n, 0);
  img.hitInstance.assign(n, -1);
  img.hitTriangle.assign(n, 0);
  img.hitPoint.assign(n, glm::dvec3(0.0));
  std::vector<uint8_t> ambiguous(n, 0);

  // Rows are interleaved over threads; every pixel is computed alone, so the result is the same
  // for any thread count.
  auto castRows = [&](int first, int step) {
    for (int y = first; y < img.height; y += step)
      for (int x = 0; x < img.width; ++x) {
        const size_t i = img.index(x, y);
        const PixelRay ray = camera.pixelRay(camera.viewport.x + x, camera.viewport.y + y);
        const RayHit hit = geometry.visible.firstHit(ray.origin, ray.direction, ray.tNear, ray.tFar);
        const PixelResult counts = countCrossings(volumes, bins.at(x, y), ray, hit, options);
        img.zpass[i] = counts.zpass;
        img.zfail[i] = counts.zfail;
        ambiguous[i] = counts.ambiguous;
        if (!hit.found()) continue;
        const glm::dvec3 p = ray.origin + hit.t * ray.direction;
        img.hitMask[i] = 1;
        img.hitInstance[i] = hit.instance;
        img.hitTriangle[i] = hit.triangle;
        img.hitPoint[i] = p;
        img.lit[i] = lightVisible(geometry, light, p);
      }
  };
  const int threads = std::clamp(options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency()),
                                 1, std::max(1, img.height));
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(castRows, t, threads);
  castRows(0, threads);
  for (std::thread& t : pool) t.join();

  markGeometryContours(geometry, camera, options.edgeRadius, img.nearEdge);
  for (const auto& [a, b] : volumeContourEdges(volumes, camera.eye))
    markNearSegment(camera, a, b, options.edgeRadius, img.nearEdge);
  for (size_t i = 0; i < n; ++i) img.nearEdge[i] |= ambiguous[i];
  if (options.markNeighbourChanges) markNeighbourChanges(img);
  return img;
}

std::vector<glm::dvec4> hitPlanes(const OracleImage& image, const std::vector<Instance>& instances) {
  std::vector<glm::dvec4> planes(image.hitInstance.size(), glm::dvec4(0.0));
  for (size_t i = 0; i < planes.size(); ++i) {
    if (image.hitInstance[i] < 0) continue;
    const Instance& inst = instances.at(size_t(image.hitInstance[i]));
    const glm::uvec3 t = inst.mesh->triangles.at(image.hitTriangle[i]);
    auto world = [&](uint32_t v) { return glm::dvec3(inst.world * glm::dvec4(inst.mesh->positions[v], 1.0)); };
    planes[i] = trianglePlane(world(t.x), world(t.y), world(t.z));
  }
  return planes;
}

}  // namespace shadowref::oracle
