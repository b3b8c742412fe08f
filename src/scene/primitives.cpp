#include "scene/primitives.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "scene/adjacency.h"

namespace shadowref {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Collects render vertices and triangles. Every primitive states which way is out for each
// triangle; the builder puts the corners in the order that makes the triangle face that way, so
// the winding (counter-clockwise seen from outside) is decided in one place.
struct MeshBuilder {
  Mesh mesh;

  uint32_t vertex(const glm::dvec3& p, const glm::dvec3& n) {
    mesh.positions.push_back(p);
    mesh.normals.push_back(glm::normalize(n));
    return static_cast<uint32_t>(mesh.positions.size() - 1);
  }
  void triangle(uint32_t a, uint32_t b, uint32_t c, const glm::dvec3& outward) {
    mesh.triangles.push_back(orientTriangle(mesh.positions, {a, b, c}, outward));
  }
  // A flat polygon (convex, corners in order around it) with its own vertices and normal n.
  void flatPolygon(const std::vector<glm::dvec3>& corners, const glm::dvec3& n) {
    const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
    for (const glm::dvec3& p : corners) vertex(p, n);
    for (uint32_t i = 1; i + 1 < corners.size(); ++i) triangle(base, base + i, base + i + 1, n);
  }
  Mesh finish(const std::string& name) {
    mesh.name = name;
    buildAdjacency(mesh);
    return std::move(mesh);
  }
};

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

glm::dvec2 onCircle(int i, int n, double radius) {
  const double a = 2.0 * kPi * i / n;
  return {radius * std::cos(a), radius * std::sin(a)};
}

}  // namespace

glm::uvec3 orientTriangle(const std::vector<glm::dvec3>& positions, glm::uvec3 t,
                          const glm::dvec3& outward) {
  const glm::dvec3 n =
      glm::cross(positions[t.y] - positions[t.x], positions[t.z] - positions[t.x]);
  if (glm::dot(n, outward) < 0.0) std::swap(t.y, t.z);
  return t;
}

Mesh makeBoxBetween(const glm::dvec3& lo, const glm::dvec3& hi) {
  require(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z, "box: every side must be positive");
  // Corner i has x from bit 0, y from bit 1, z from bit 2: each coordinate is lo or hi, copied.
  std::array<glm::dvec3, 8> c;
  for (int i = 0; i < 8; ++i) c[i] = {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
  MeshBuilder b;
  // Each face: its four corners in order around it, and its outward normal.
  b.flatPolygon({c[0], c[2], c[6], c[4]}, {-1, 0, 0});
  b.flatPolygon({c[1], c[3], c[7], c[5]}, {1, 0, 0});
  b.flatPolygon({c[0], c[1], c[5], c[4]}, {0, -1, 0});
  b.flatPolygon({c[2], c[3], c[7], c[6]}, {0, 1, 0});
  b.flatPolygon({c[0], c[1], c[3], c[2]}, {0, 0, -1});
  b.flatPolygon({c[4], c[5], c[7], c[6]}, {0, 0, 1});
  return b.finish("box");
}

Mesh makeBox(const glm::dvec3& size) { return makeBoxBetween(-0.5 * size, 0.5 * size); }

Mesh makePlane(const glm::dvec2& size, double thickness) {
  require(thickness > 0.0, "plane: thickness must be positive");
  Mesh m = makeBoxBetween({-0.5 * size.x, -thickness, -0.5 * size.y}, {0.5 * size.x, 0.0, 0.5 * size.y});
  m.name = "plane";
  return m;
}

void appendLatLongCell(const LatLongGrid& g, int ring, int slice, std::vector<glm::uvec3>& out) {
  const uint32_t a = g.at(ring, slice), b = g.at(ring, slice + 1);
  const uint32_t c = g.at(ring + 1, slice), d = g.at(ring + 1, slice + 1);
  auto add = [&](uint32_t x, uint32_t y, uint32_t z) {
    // Star-shaped around the origin: the centroid points out.
    const glm::dvec3 centroid = (g.positions[x] + g.positions[y] + g.positions[z]) / 3.0;
    out.push_back(orientTriangle(g.positions, {x, y, z}, centroid));
  };
  if (ring == 0) {
    add(a, c, d);
  } else if (ring == g.stacks - 1) {
    add(a, b, c);
  } else {
    add(a, c, d);
    add(a, d, b);
  }
}

Mesh meshFromLatLongGrid(const LatLongGrid& grid) {
  Mesh m;
  m.positions = grid.positions;
  for (int ring = 0; ring < grid.stacks; ++ring)
    for (int s = 0; s < grid.slices; ++s) appendLatLongCell(grid, ring, s, m.triangles);
  computeSmoothNormals(m);
  m.name = "surface";
  buildAdjacency(m);
  return m;
}

Mesh makeSphere(double radius, int slices, int stacks) {
  require(radius > 0.0 && slices >= 3 && stacks >= 2, "sphere: radius > 0, slices >= 3, stacks >= 2");
  auto surface = [radius](double theta, double phi) {
    const double rho = radius * std::sin(phi);
    return glm::dvec3(rho * std::cos(theta), radius * std::cos(phi), rho * std::sin(theta));
  };
  Mesh m = makeLatLongSurface(surface, slices, stacks);
  for (size_t i = 0; i < m.positions.size(); ++i) m.normals[i] = glm::normalize(m.positions[i]);
  m.name = "sphere";
  return m;
}

Mesh makeCylinder(double radius, double height, int slices) {
  require(radius > 0.0 && height > 0.0 && slices >= 3, "cylinder: radius, height > 0, slices >= 3");
  const double y0 = -0.5 * height, y1 = 0.5 * height;
  std::vector<glm::dvec3> bottom, top;
  std::vector<glm::dvec3> radial;
  for (int i = 0; i < slices; ++i) {
    const glm::dvec2 c = onCircle(i, slices, radius);
    bottom.push_back({c.x, y0, c.y});
    top.push_back({c.x, y1, c.y});
    radial.push_back({c.x, 0.0, c.y});
  }
  MeshBuilder b;
  // Smooth side: one vertex per ring point, shared by the quads on either side.
  const uint32_t sideBase = static_cast<uint32_t>(b.mesh.positions.size());
  for (int i = 0; i < slices; ++i) {
    b.vertex(bottom[i], radial[i]);
    b.vertex(top[i], radial[i]);
  }
  for (int i = 0; i < slices; ++i) {
    const int j = (i + 1) % slices;
    const uint32_t b0 = sideBase + 2 * i, t0 = b0 + 1, b1 = sideBase + 2 * j, t1 = b1 + 1;
    const glm::dvec3 out = radial[i] + radial[j];
    b.triangle(b0, t0, b1, out);
    b.triangle(b1, t0, t1, out);
  }
  // Flat caps around a centre vertex (no slivers).
  for (int cap = 0; cap < 2; ++cap) {
    const auto& ring = cap ? top : bottom;
    const glm::dvec3 n(0.0, cap ? 1.0 : -1.0, 0.0);
    const uint32_t centre = b.vertex({0.0, cap ? y1 : y0, 0.0}, n);
    const uint32_t base = static_cast<uint32_t>(b.mesh.positions.size());
    for (const glm::dvec3& p : ring) b.vertex(p, n);
    for (int i = 0; i < slices; ++i) b.triangle(centre, base + i, base + (i + 1) % slices, n);
  }
  return b.finish("cylinder");
}

Mesh makeCone(double radius, double height, int slices) {
  require(radius > 0.0 && height > 0.0 && slices >= 3, "cone: radius, height > 0, slices >= 3");
  const double y0 = -0.5 * height;
  const glm::dvec3 apex(0.0, 0.5 * height, 0.0);
  std::vector<glm::dvec3> ring;
  for (int i = 0; i < slices; ++i) {
    const glm::dvec2 c = onCircle(i, slices, radius);
    ring.push_back({c.x, y0, c.y});
  }
  // The side normal at angle a: (h cos a, r, h sin a), perpendicular to the slant.
  auto sideNormal = [&](double a) {
    return glm::dvec3(height * std::cos(a), radius, height * std::sin(a));
  };
  MeshBuilder b;
  const uint32_t ringBase = static_cast<uint32_t>(b.mesh.positions.size());
  for (int i = 0; i < slices; ++i) b.vertex(ring[i], sideNormal(2.0 * kPi * i / slices));
  for (int i = 0; i < slices; ++i) {
    const int j = (i + 1) % slices;
    // The apex has one render vertex per slice with the normal halfway between: same position.
    const glm::dvec3 n = sideNormal(2.0 * kPi * (i + 0.5) / slices);
    const uint32_t top = b.vertex(apex, n);
    b.triangle(ringBase + i, top, ringBase + j, n);
  }
  const glm::dvec3 down(0.0, -1.0, 0.0);
  const uint32_t centre = b.vertex({0.0, y0, 0.0}, down);
  const uint32_t base = static_cast<uint32_t>(b.mesh.positions.size());
  for (const glm::dvec3& p : ring) b.vertex(p, down);
  for (int i = 0; i < slices; ++i) b.triangle(centre, base + i, base + (i + 1) % slices, down);
  return b.finish("cone");
}

Mesh makeTorus(double majorRadius, double minorRadius, int majorSegments, int minorSegments) {
  require(majorRadius > minorRadius && minorRadius > 0.0 && majorSegments >= 3 && minorSegments >= 3,
          "torus: major radius > minor radius > 0, segments >= 3");
  MeshBuilder b;
  auto index = [&](int i, int j) {
    return static_cast<uint32_t>((i % majorSegments) * minorSegments + (j % minorSegments));
  };
  for (int i = 0; i < majorSegments; ++i) {
    const double u = 2.0 * kPi * i / majorSegments;
    for (int j = 0; j < minorSegments; ++j) {
      const double v = 2.0 * kPi * j / minorSegments;
      const glm::dvec3 n(std::cos(v) * std::cos(u), std::sin(v), std::cos(v) * std::sin(u));
      const double rho = majorRadius + minorRadius * std::cos(v);
      b.vertex({rho * std::cos(u), minorRadius * std::sin(v), rho * std::sin(u)}, n);
    }
  }
  for (int i = 0; i < majorSegments; ++i)
    for (int j = 0; j < minorSegments; ++j) {
      const uint32_t a = index(i, j), c = index(i + 1, j), d = index(i + 1, j + 1), e = index(i, j + 1);
      const glm::dvec3 out = b.mesh.normals[a] + b.mesh.normals[c] + b.mesh.normals[d] + b.mesh.normals[e];
      b.triangle(a, c, d, out);
      b.triangle(a, d, e, out);
    }
  return b.finish("torus");
}

Mesh makeExtrudedPolygon(const std::vector<glm::dvec2>& polygon, double height) {
  require(polygon.size() >= 3 && height > 0.0, "prism: at least 3 corners and a positive height");
  const double y0 = -0.5 * height, y1 = 0.5 * height;
  const size_t n = polygon.size();
  std::vector<glm::dvec3> bottom, top;
  glm::dvec2 centre(0.0);
  for (const glm::dvec2& p : polygon) {
    bottom.push_back({p.x, y0, p.y});
    top.push_back({p.x, y1, p.y});
    centre += p / static_cast<double>(n);
  }
  MeshBuilder b;
  for (size_t i = 0; i < n; ++i) {
    const size_t j = (i + 1) % n;
    // Outward normal of side i: perpendicular to the side, away from the polygon's centre.
    const glm::dvec2 d = polygon[j] - polygon[i];
    glm::dvec3 out(d.y, 0.0, -d.x);
    const glm::dvec2 mid = 0.5 * (polygon[i] + polygon[j]) - centre;
    if (out.x * mid.x + out.z * mid.y < 0.0) out = -out;
    b.flatPolygon({bottom[i], bottom[j], top[j], top[i]}, out);
  }
  b.flatPolygon(bottom, {0.0, -1.0, 0.0});
  b.flatPolygon(top, {0.0, 1.0, 0.0});
  return b.finish("prism");
}

Mesh makePrism(int sides, double radius, double height) {
  require(sides >= 3 && radius > 0.0, "prism: sides >= 3, radius > 0");
  std::vector<glm::dvec2> polygon;
  for (int i = 0; i < sides; ++i) polygon.push_back(onCircle(i, sides, radius));
  return makeExtrudedPolygon(polygon, height);
}

}  // namespace shadowref
