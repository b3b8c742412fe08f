#include "shadow/soft_lights.h"

#include <cmath>

namespace shadowref {

namespace {

std::vector<glm::dvec3> squareOffsets(int axis, double s) {
  // The 8 points of a 3x3 grid without its centre, in the plane orthogonal to `axis`.
  std::vector<glm::dvec3> out;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j) {
      if (i == 0 && j == 0) continue;
      glm::dvec3 d(0.0);
      d[(axis + 1) % 3] = i * s;
      d[(axis + 2) % 3] = j * s;
      out.push_back(d);
    }
  return out;
}

std::vector<glm::dvec3> sphereOffsets(double s) {
  std::vector<glm::dvec3> out;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      glm::dvec3 d(0.0);
      d[axis] = sign * s;
      out.push_back(d);
    }
  const double k = s / std::sqrt(3.0);
  for (int i = 0; i < 8; ++i) out.push_back(glm::dvec3((i & 1) ? k : -k, (i & 2) ? k : -k, (i & 4) ? k : -k));
  return out;
}

// 16 points evenly spaced along the perimeter of a square of side `side` (4 per edge, starting at
// a corner), in the plane spanned by u and v.
std::vector<glm::dvec3> areaEdgeOffsets(const glm::dvec3& u, const glm::dvec3& v, double side) {
  std::vector<glm::dvec3> out;
  const double h = side / 2.0;
  const glm::dvec2 corners[4] = {{-h, -h}, {h, -h}, {h, h}, {-h, h}};
  for (int e = 0; e < 4; ++e) {
    const glm::dvec2 a = corners[e], b = corners[(e + 1) % 4];
    for (int k = 0; k < 4; ++k) {
      const glm::dvec2 p = a + (b - a) * (double(k) / 4.0);
      out.push_back(u * p.x + v * p.y);
    }
  }
  return out;
}

}  // namespace

std::vector<Light> expandSoftLight(const Light& light) {
  if (light.soft == SoftShape::None || light.type == LightType::Directional) return {light};
  std::vector<glm::dvec3> offsets;
  bool includeCentre = true;
  switch (light.soft) {
    case SoftShape::SquareX: offsets = squareOffsets(0, light.softSpacing); break;
    case SoftShape::SquareY: offsets = squareOffsets(1, light.softSpacing); break;
    case SoftShape::SquareZ: offsets = squareOffsets(2, light.softSpacing); break;
    case SoftShape::Sphere14: offsets = sphereOffsets(light.softSpacing); break;
    case SoftShape::AreaEdge16: {
      const glm::dvec3 n = glm::normalize(light.direction);
      const glm::dvec3 helper = std::fabs(n.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
      const glm::dvec3 u = glm::normalize(glm::cross(helper, n));
      offsets = areaEdgeOffsets(u, glm::cross(n, u), light.softSpacing);
      includeCentre = false;
      break;
    }
    case SoftShape::None: break;
  }
  std::vector<Light> out;
  if (includeCentre) out.push_back(light);
  for (const glm::dvec3& d : offsets) {
    Light l = light;
    l.position += d;
    out.push_back(l);
  }
  const double count = double(out.size());
  for (size_t i = 0; i < out.size(); ++i) {
    out[i].color = light.color / count;
    out[i].soft = SoftShape::None;
    out[i].name = light.name + "." + std::to_string(i);
  }
  return out;
}

}  // namespace shadowref
