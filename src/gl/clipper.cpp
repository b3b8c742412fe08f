#include "gl/clipper.h"

#include <utility>

namespace shadowref {

namespace {

enum class Plane { Near, Far, Left, Right, Bottom, Top, MinW };

// Signed distance to the plane in clip space; >= 0 is inside.
double distance(Plane plane, const glm::dvec4& p, double g) {
  switch (plane) {
    case Plane::Near: return p.z + p.w;
    case Plane::Far: return p.w - p.z;
    case Plane::Left: return g * p.w + p.x;
    case Plane::Right: return g * p.w - p.x;
    case Plane::Bottom: return g * p.w + p.y;
    case Plane::Top: return g * p.w - p.y;
    case Plane::MinW: return p.w - kMinClipW;
  }
  return 0.0;
}

// Puts an intersection exactly on its plane. Interpolation alone loses the plane's own coordinate
// when the outside end is far beyond it: x = 3e20 + 0.75 (-1e20 - 3e20) cancels to 0, not to the
// guard band -G w = -32768, and half the viewport goes missing.
void placeOnPlane(Plane plane, glm::dvec4& p, double g) {
  switch (plane) {
    case Plane::Near: p.z = -p.w; break;
    case Plane::Far: p.z = p.w; break;
    case Plane::Left: p.x = -g * p.w; break;
    case Plane::Right: p.x = g * p.w; break;
    case Plane::Bottom: p.y = -g * p.w; break;
    case Plane::Top: p.y = g * p.w; break;
    case Plane::MinW: p.w = kMinClipW; break;
  }
}

// The point where the edge from `inside` to `outside` crosses the plane. Always called with the
// inside end first, so both triangles sharing an edge compute the same point.
ClipVertex intersect(Plane plane, double g, const ClipVertex& inside, double dIn, const ClipVertex& outside,
                     double dOut, int varyingCount) {
  const double t = dIn / (dIn - dOut);
  ClipVertex r;
  r.position = inside.position + t * (outside.position - inside.position);
  placeOnPlane(plane, r.position, g);
  for (int i = 0; i < varyingCount; ++i)
    r.varyings[i] = inside.varyings[i] + t * (outside.varyings[i] - inside.varyings[i]);
  return r;
}

// One Sutherland–Hodgman step [Sutherland & Hodgman 1974].
void clipAgainst(Plane plane, double g, const std::vector<ClipVertex>& in, int varyingCount,
                 std::vector<ClipVertex>& out) {
  out.clear();
  const size_t n = in.size();
  for (size_t i = 0; i < n; ++i) {
    const ClipVertex& a = in[i];
    const ClipVertex& b = in[(i + 1) % n];
    const double da = distance(plane, a.position, g);
    const double db = distance(plane, b.position, g);
    const bool aIn = da >= 0.0, bIn = db >= 0.0;
    if (aIn) out.push_back(a);
    if (aIn && !bIn) out.push_back(intersect(plane, g, a, da, b, db, varyingCount));
    if (!aIn && bIn) out.push_back(intersect(plane, g, b, db, a, da, varyingCount));
  }
}

bool inside(Plane plane, const glm::dvec4& p, double g) { return distance(plane, p, g) >= 0.0; }

}  // namespace

bool insideAllPlanes(const ClipVertex* v, int count, const ClipPlanes& planes) {
  const double g = planes.guardBand;
  for (int i = 0; i < count; ++i) {
    const glm::dvec4& p = v[i].position;
    if (planes.nearPlane && !inside(Plane::Near, p, g)) return false;
    if (planes.farPlane && !inside(Plane::Far, p, g)) return false;
    if (!inside(Plane::Left, p, g) || !inside(Plane::Right, p, g) || !inside(Plane::Bottom, p, g) ||
        !inside(Plane::Top, p, g) || !inside(Plane::MinW, p, g))
      return false;
  }
  return true;
}

void clipPolygon(const std::vector<ClipVertex>& in, const ClipPlanes& planes, int varyingCount,
                 std::vector<ClipVertex>& out, std::vector<ClipVertex>& scratch) {
  out = in;
  const Plane order[] = {Plane::Near, Plane::Far, Plane::Left, Plane::Right,
                         Plane::Bottom, Plane::Top, Plane::MinW};
  for (Plane plane : order) {
    if (plane == Plane::Near && !planes.nearPlane) continue;
    if (plane == Plane::Far && !planes.farPlane) continue;
    bool allInside = true;
    for (const ClipVertex& v : out) allInside = allInside && inside(plane, v.position, planes.guardBand);
    if (allInside) continue;
    clipAgainst(plane, planes.guardBand, out, varyingCount, scratch);
    std::swap(out, scratch);
    if (out.size() < 3) {
      out.clear();
      return;
    }
  }
}

}  // namespace shadowref
