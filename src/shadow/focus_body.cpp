#include "shadow/focus_body.h"

namespace shadowref {

namespace {

// The corner indices of each face of a hexahedron in frustumCorners order.
constexpr int kHexFaces[6][4] = {
    {0, 1, 2, 3},  // near
    {4, 5, 6, 7},  // far
    {0, 3, 7, 4},  // left
    {1, 5, 6, 2},  // right
    {0, 4, 5, 1},  // bottom
    {3, 2, 6, 7},  // top
};

// The plane through a face, turned so that `inside` is on its positive side.
HalfSpace planeThrough(const ConvexPolygon& face, const glm::dvec3& inside) {
  // Newell's normal: robust for a slightly non-planar or nearly degenerate quad.
  glm::dvec3 n(0.0), centre(0.0);
  for (size_t i = 0; i < face.size(); ++i) {
    const glm::dvec3& a = face[i];
    const glm::dvec3& b = face[(i + 1) % face.size()];
    n += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    centre += a;
  }
  centre /= double(face.size());
  const double len = glm::length(n);
  if (len > 0.0) n /= len;
  HalfSpace h{n, -glm::dot(n, centre)};
  if (h.signedDistance(inside) < 0.0) h = HalfSpace{-n, -h.d};
  return h;
}

}  // namespace

ConvexPolygon clipPolygon(const ConvexPolygon& polygon, const HalfSpace& plane) {
  ConvexPolygon out;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const glm::dvec3& a = polygon[i];
    const glm::dvec3& b = polygon[(i + 1) % polygon.size()];
    const double da = plane.signedDistance(a), db = plane.signedDistance(b);
    if (da >= 0.0) out.push_back(a);
    if ((da >= 0.0) != (db >= 0.0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

ConvexBody hexahedron(const std::array<glm::dvec3, 8>& c) {
  glm::dvec3 centroid(0.0);
  for (const glm::dvec3& p : c) centroid += p;
  centroid /= 8.0;
  ConvexBody body;
  for (const auto& f : kHexFaces) {
    ConvexPolygon face{c[size_t(f[0])], c[size_t(f[1])], c[size_t(f[2])], c[size_t(f[3])]};
    body.planes.push_back(planeThrough(face, centroid));
    body.faces.push_back(std::move(face));
  }
  return body;
}

ConvexBody boxBody(const Aabb& b) {
  const std::array<glm::dvec3, 8> c = {
      glm::dvec3{b.min.x, b.min.y, b.min.z}, glm::dvec3{b.max.x, b.min.y, b.min.z},
      glm::dvec3{b.max.x, b.max.y, b.min.z}, glm::dvec3{b.min.x, b.max.y, b.min.z},
      glm::dvec3{b.min.x, b.min.y, b.max.z}, glm::dvec3{b.max.x, b.min.y, b.max.z},
      glm::dvec3{b.max.x, b.max.y, b.max.z}, glm::dvec3{b.min.x, b.max.y, b.max.z}};
  ConvexBody body = hexahedron(c);
  // Exact axis planes (a flat box has no volume, and Newell's normal of its thin sides is zero).
  body.planes = {HalfSpace{{1, 0, 0}, -b.min.x}, HalfSpace{{-1, 0, 0}, b.max.x}, HalfSpace{{0, 1, 0}, -b.min.y},
                 HalfSpace{{0, -1, 0}, b.max.y}, HalfSpace{{0, 0, 1}, -b.min.z}, HalfSpace{{0, 0, -1}, b.max.z}};
  return body;
}

ConvexBody clipVolumeBody(const glm::dmat4& worldToClip) {
  const glm::dmat4 inverse = glm::inverse(worldToClip);
  std::array<glm::dvec3, 8> c;
  for (int i = 0; i < 8; ++i) {
    const double x = (i == 1 || i == 2 || i == 5 || i == 6) ? 1.0 : -1.0;
    const double y = (i == 2 || i == 3 || i == 6 || i == 7) ? 1.0 : -1.0;
    const double z = i < 4 ? -1.0 : 1.0;
    const glm::dvec4 h = inverse * glm::dvec4(x, y, z, 1.0);
    c[size_t(i)] = glm::dvec3(h) / h.w;
  }
  return hexahedron(c);
}

std::vector<glm::dvec3> intersectionVertices(const std::vector<ConvexBody>& bodies) {
  std::vector<glm::dvec3> out;
  for (size_t i = 0; i < bodies.size(); ++i)
    for (const ConvexPolygon& face : bodies[i].faces) {
      ConvexPolygon p = face;
      for (size_t j = 0; j < bodies.size() && p.size() >= 3; ++j)
        if (j != i)
          for (const HalfSpace& h : bodies[j].planes) p = clipPolygon(p, h);
      if (p.size() >= 3) out.insert(out.end(), p.begin(), p.end());
    }
  return out;
}

std::vector<glm::dvec3> focusBody(const std::array<glm::dvec3, 8>& frustum, const Aabb& sceneBox,
                                  const glm::dmat4& lightClip) {
  if (sceneBox.empty()) return {};
  return intersectionVertices({hexahedron(frustum), boxBody(sceneBox), clipVolumeBody(lightClip)});
}

}  // namespace shadowref
