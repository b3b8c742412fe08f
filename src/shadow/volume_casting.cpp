#include "shadow/volume_casting.h"

#include <cstdio>

#include "scene/adjacency.h"

namespace shadowref {

VolumeCasting volumeCastingOf(const Mesh& mesh) {
  if (mesh.topology != Topology::Closed || mesh.inconsistentEdges > 0 || mesh.mixedWinding)
    return VolumeCasting::TwoSided;
  return mesh.insideOut ? VolumeCasting::Reversed : VolumeCasting::Silhouette;
}

std::string castingWarning(const Mesh& mesh) {
  using std::to_string;
  const std::string name = "mesh '" + (mesh.name.empty() ? std::string("?") : mesh.name) + "'";
  switch (volumeCastingOf(mesh)) {
    case VolumeCasting::Silhouette: return {};
    case VolumeCasting::Reversed: {
      char volume[40];
      std::snprintf(volume, sizeof volume, "%g", mesh.enclosedVolume);
      return name + " is inside out (closed, but it encloses a negative volume, " + volume +
             ": its triangles are wound clockwise seen from outside); the shadow volumes take its winding as "
             "reversed";
    }
    case VolumeCasting::TwoSided: break;
  }
  std::string what;
  auto add = [&](const std::string& part) { what += (what.empty() ? "" : ", ") + part; };
  if (mesh.openEdges) add("open (" + to_string(mesh.openEdges) + " edges with one triangle)");
  if (mesh.nonManifoldEdges)
    add("non-manifold (" + to_string(mesh.nonManifoldEdges) + " edges with three or more triangles)");
  if (mesh.inconsistentEdges)
    add("inconsistently wound (" + to_string(mesh.inconsistentEdges) +
        " edges whose two triangles run them the same way)");
  if (mesh.mixedWinding) {
    const ClosedPartWinding parts = closedPartWinding(mesh);
    add("partly inside out (" + to_string(parts.insideOut) + " of its " + to_string(parts.parts) +
        " closed parts enclose a negative volume outside every other part)");
  }
  return name + " is " + what +
         "; it casts its shadow as a two-sided surface: the shadow volumes close one volume per triangle, turned "
         "towards the light";
}

}  // namespace shadowref
