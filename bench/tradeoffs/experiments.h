// The configurations the trade-off bench measures: the documents' experiments
// ([Kuhn 2016, §5.3, §5.4.1, §5.4.2]; [Hempe 2004, §6.1]) and the choices a user trades (map size,
// PCF, bias, depth format, far plane). Each is a scene file, -D overrides and a shadow method.
#pragma once

#include <string>
#include <vector>

namespace shadowref::bench {

// What the renderer's shadow is compared with.
enum class Reference {
  HardLight,   // the light as a point: the oracle's shadow ray per pixel (src/oracle)
  AreaSquare,  // the square [-s, s]^2 around the light in its horizontal plane (square_y's span)
  AreaSphere,  // the sphere of radius s around the light (sphere14's points lie on it)
};
const char* name(Reference reference);

struct Experiment {
  std::string group;    // houses, lights, counting, soft, map_size, pcf, bias, depth, far
  std::string scene;    // room, pumpkins, city, outdoor: scenes/<scene>.yaml
  std::string variant;  // what changes within the group, e.g. "houses=8 single"
  std::string method;   // none, zpass, zfail, auto, shadowmap, tsm
  std::vector<std::string> overrides;  // -D key=value, image size included
  Reference reference = Reference::HardLight;
  double softSpacing = 0.0;  // the reference light's size (AreaSquare, AreaSphere)
  // The error-against-time plot this row belongs to ("" for none): one plot per scene, so that
  // every point on it renders the same picture.
  std::string plot;
};

struct BenchSize {
  int width = 400, height = 320;
};

std::vector<Experiment> allExperiments(const BenchSize& size);

}  // namespace shadowref::bench
