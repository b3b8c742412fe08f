// Shared helpers of the scene generators (generators.h): portable seeded random numbers and a small
// builder that appends meshes, materials and nodes to a Scene.
#pragma once

#include <cmath>
#include <memory>
#include <random>
#include <string>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace shadowref::generator {

// std::mt19937's sequence is fixed by the standard, the std:: distributions are not (they differ
// between library versions), so the mapping to numbers is done here, by hand.
class SeededRandom {
 public:
  explicit SeededRandom(uint32_t seed) : engine_(seed) {}
  // Uniform in [lo, hi): the 32 random bits as a fraction of 2^32.
  double uniform(double lo, double hi) { return lo + (hi - lo) * (static_cast<double>(engine_()) / 4294967296.0); }
  // Uniform integer in [0, n) (the modulo bias is irrelevant for n this small).
  int below(int n) { return static_cast<int>(engine_() % static_cast<uint32_t>(n)); }

 private:
  std::mt19937 engine_;
};

inline glm::dmat4 translation(const glm::dvec3& t) {
  glm::dmat4 m(1.0);
  m[3] = glm::dvec4(t, 1.0);
  return m;
}

// Rotation about y by quarter turns, with exact 0 and ±1 entries.
inline glm::dmat4 quarterTurnsY(int quarters) {
  static const double c[4] = {1.0, 0.0, -1.0, 0.0}, s[4] = {0.0, 1.0, 0.0, -1.0};
  const int q = ((quarters % 4) + 4) % 4;
  glm::dmat4 m(1.0);
  m[0] = glm::dvec4(c[q], 0.0, -s[q], 0.0);
  m[2] = glm::dvec4(s[q], 0.0, c[q], 0.0);
  return m;
}

// Rotation about y by an angle in radians.
inline glm::dmat4 rotationY(double radians) {
  glm::dmat4 m(1.0);
  const double c = std::cos(radians), s = std::sin(radians);
  m[0] = glm::dvec4(c, 0.0, -s, 0.0);
  m[2] = glm::dvec4(s, 0.0, c, 0.0);
  return m;
}

inline Material material(const std::string& name, const glm::dvec3& diffuse, const glm::dvec3& specular = glm::dvec3(0.0),
                         double shininess = 32.0) {
  Material m;
  m.name = name;
  m.ambient = diffuse;
  m.diffuse = diffuse;
  m.specular = specular;
  m.shininess = shininess;
  return m;
}

class SceneBuilder {
 public:
  explicit SceneBuilder(Scene& scene) : scene_(scene) {}

  int mesh(Mesh m, const std::string& name) {
    m.name = name;
    scene_.meshes.push_back(std::make_shared<Mesh>(std::move(m)));
    return static_cast<int>(scene_.meshes.size() - 1);
  }
  int material(Material m) {
    scene_.materials.push_back(std::move(m));
    return static_cast<int>(scene_.materials.size() - 1);
  }
  static Node node(const std::string& name, int mesh, int material, const glm::dmat4& local = glm::dmat4(1.0)) {
    Node n;
    n.name = name;
    n.mesh = mesh;
    n.material = material;
    n.local = local;
    return n;
  }
  static Node group(const std::string& name, const glm::dmat4& local = glm::dmat4(1.0)) {
    return node(name, -1, 0, local);
  }
  void root(Node n) { scene_.roots.push_back(std::move(n)); }
  Scene& scene() { return scene_; }

 private:
  Scene& scene_;
};

}  // namespace shadowref::generator
