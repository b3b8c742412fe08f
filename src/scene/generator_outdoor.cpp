// The outdoor scene of [Hempe 2004, §6]: a wide terrain whose shadows must stay sharp far and near
// — the case trapezoidal shadow maps are made for — under a low directional light.
#include <cmath>

#include "scene/generator_support.h"
#include "scene/generators.h"
#include "scene/primitives.h"

namespace shadowref {

using namespace generator;

void addOutdoor(Scene& scene, const OutdoorOptions& o) {
  SceneBuilder b(scene);
  SeededRandom random(o.seed);
  const int grass = b.material(material("grass", {0.35, 0.55, 0.25}));
  const int hill = b.material(material("hill", {0.4, 0.5, 0.28}));
  const int bark = b.material(material("bark", {0.4, 0.28, 0.18}));
  const int leaves = b.material(material("leaves", {0.15, 0.45, 0.15}, glm::dvec3(0.05), 8.0));
  const int metal = b.material(material("pole", {0.6, 0.6, 0.62}, glm::dvec3(0.5), 64.0));

  const double half = 0.5 * o.size;
  Node outdoor = SceneBuilder::group("outdoor");
  outdoor.children.push_back(SceneBuilder::node("ground", b.mesh(makePlane({o.size, o.size}, 1.0), "terrain"), grass));

  // Gentle hills: flat ellipsoids sunk into the ground, in the distance and to the sides.
  for (int i = 0; i < 5; ++i) {
    const double rx = random.uniform(15.0, 35.0), rz = random.uniform(15.0, 35.0), ry = random.uniform(3.0, 7.0);
    const double x = random.uniform(-0.7, 0.7) * half, z = random.uniform(-0.9, -0.2) * half;
    auto ellipsoid = [=](double theta, double phi) {
      return glm::dvec3(rx * std::sin(phi) * std::cos(theta), ry * std::cos(phi), rz * std::sin(phi) * std::sin(theta));
    };
    outdoor.children.push_back(SceneBuilder::node("hill" + std::to_string(i),
                                                  b.mesh(makeLatLongSurface(ellipsoid, 32, 12), "hill"), hill,
                                                  translation({x, -0.4 * ry, z})));
  }

  // Trees of three sizes (trunk + crown), scattered in front of the camera.
  struct TreeMeshes {
    int trunk, crown;
    double trunkHeight, crownHeight;
  };
  TreeMeshes sizes[3];
  for (int s = 0; s < 3; ++s) {
    const double scale = 0.7 + 0.3 * s;
    sizes[s] = {b.mesh(makeCylinder(0.25 * scale, 2.0 * scale, 8), "tree_trunk"),
                b.mesh(makeCone(1.6 * scale, 5.0 * scale, 12), "tree_crown"), 2.0 * scale, 5.0 * scale};
  }
  for (int i = 0; i < o.trees; ++i) {
    const TreeMeshes& t = sizes[random.below(3)];
    const glm::dvec3 at(random.uniform(-60.0, 60.0), 0.0, random.uniform(-150.0, 20.0));
    Node tree = SceneBuilder::group("tree" + std::to_string(i), translation(at));
    tree.children.push_back(SceneBuilder::node("trunk", t.trunk, bark, translation({0.0, 0.5 * t.trunkHeight, 0.0})));
    tree.children.push_back(SceneBuilder::node(
        "crown", t.crown, leaves, translation({0.0, t.trunkHeight + 0.5 * t.crownHeight - 0.3, 0.0})));
    outdoor.children.push_back(std::move(tree));
  }

  // A line of poles along a path, from near the camera into the distance: thin shadows at every
  // distance are what shows the shadow map's resolution.
  const int pole = b.mesh(makeCylinder(0.12, 6.0, 8), "pole");
  for (int i = 0; i < o.poles; ++i)
    outdoor.children.push_back(
        SceneBuilder::node("pole" + std::to_string(i), pole, metal, translation({6.0, 3.0, 15.0 - 14.0 * i})));
  b.root(std::move(outdoor));

  // Low sun, about 25 degrees above the horizon, from behind on the right: the long shadows run
  // across the ground towards the camera, near and far.
  Light sun;
  sun.name = "sun";
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::dvec3(-0.75, -0.42, 0.5));
  sun.color = glm::dvec3(1.0);
  scene.lights.push_back(sun);

  if (o.setView) {
    scene.width = 800;
    scene.height = 640;
    scene.ambient = glm::dvec3(0.25);
    scene.camera.eye = {0.0, 2.0, 30.0};
    scene.camera.target = {0.0, 1.0, -20.0};
    scene.camera.up = {0.0, 1.0, 0.0};
    scene.camera.fovYDegrees = 55.0;
    scene.camera.nearPlane = 0.5;
    scene.camera.farPlane = 300.0;
  }
}

}  // namespace shadowref
