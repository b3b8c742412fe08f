#include "views/volume_colours.h"

#include <algorithm>
#include <cmath>

namespace shadowref::views {

namespace {

glm::dvec3 fullHue(double degrees) {
  const double h6 = degrees / 60.0;
  const double f = h6 - std::floor(h6);
  switch (int(std::floor(h6)) % 6) {
    case 0: return {1.0, f, 0.0};
    case 1: return {1.0 - f, 1.0, 0.0};
    case 2: return {0.0, 1.0, f};
    case 3: return {0.0, 1.0 - f, 1.0};
    case 4: return {f, 0.0, 1.0};
    default: return {1.0, 0.0, 1.0 - f};
  }
}

}  // namespace

double hueDegrees(const glm::dvec3& c) {
  const double mx = std::max({c.r, c.g, c.b}), mn = std::min({c.r, c.g, c.b});
  const double d = mx - mn;
  if (!(d > 0.0)) return 0.0;
  double h = 0.0;
  if (mx == c.r) h = std::fmod((c.g - c.b) / d, 6.0);
  else if (mx == c.g) h = (c.b - c.r) / d + 2.0;
  else h = (c.r - c.g) / d + 4.0;
  h *= 60.0;
  return h < 0.0 ? h + 360.0 : h;
}

double saturation(const glm::dvec3& c) {
  const double mx = std::max({c.r, c.g, c.b}), mn = std::min({c.r, c.g, c.b});
  return mx > 0.0 ? (mx - mn) / mx : 0.0;
}

double hueDistance(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 360.0);
  return std::min(d, 360.0 - d);
}

std::vector<std::array<glm::dvec3, 2>> volumeColours(std::span<const glm::dvec3> materialColours, size_t lights) {
  std::vector<double> taken;
  for (const glm::dvec3& c : materialColours)
    if (saturation(c) >= kHuedSaturation) taken.push_back(hueDegrees(c));
  std::vector<double> chosen;
  for (size_t k = 0; k < 2 * lights; ++k) {
    double best = 0.0, bestDistance = -1.0;
    for (int h = 0; h < 360; ++h) {
      double nearest = 180.0;
      for (double t : taken) nearest = std::min(nearest, hueDistance(h, t));
      if (nearest > bestDistance) {
        bestDistance = nearest;
        best = h;
      }
    }
    taken.push_back(best);
    chosen.push_back(best);
  }
  std::vector<std::array<glm::dvec3, 2>> out(lights);
  for (size_t l = 0; l < lights; ++l) out[l] = {fullHue(chosen[2 * l]), fullHue(chosen[2 * l + 1])};
  return out;
}

std::vector<std::array<glm::dvec3, 2>> volumeColours(const Scene& scene) {
  std::vector<glm::dvec3> colours;
  for (const Material& m : scene.materials) colours.push_back(m.diffuse);
  return volumeColours(colours, scene.lights.size());
}

}  // namespace shadowref::views
