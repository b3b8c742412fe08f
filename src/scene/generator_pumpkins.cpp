// The Halloween porch of [Kuhn 2016, Fig. 5.2 / 5.8].
#include <cmath>

#include "scene/generator_support.h"
#include "scene/generators.h"
#include "scene/primitives.h"
#include "scene/pumpkin.h"

namespace shadowref {

using namespace generator;

namespace {

constexpr double kDegrees = 3.14159265358979323846 / 180.0;

struct PumpkinPlace {
  double x, z, radius, turnDegrees;
};

// The lantern first; two pumpkins sit in front of its face, where its light falls.
constexpr PumpkinPlace kPumpkins[7] = {
    {0.5, 1.0, 0.45, -90.0},  // the hollow lantern; its face looks to the front (+z)
    {1.3, 2.3, 0.26, 15.0},   {0.3, 2.7, 0.3, 40.0},   {-1.7, 0.3, 0.36, 75.0},
    {2.5, 0.4, 0.4, 110.0},   {-2.6, -1.7, 0.38, 5.0}, {1.6, -1.9, 0.3, 60.0},
};

// The candle flame, in lantern radii in the lantern's own frame (+x is the face): a quarter radius
// below the centre and off every plane of symmetry. Not at the centre: the inner skin is the outer
// one scaled about the centre, so every rim quad lies in a plane through it, and a light there
// would be in the plane of all 204 rim triangles — N · (L − V) = 0 ([Kuhn 2016, §4.3.4]), each
// rim's facing left to rounding and its surface lying exactly in a shadow-volume side (z-fighting
// in the stencil). This offset keeps the light at least |cos| 0.038 off every lantern triangle's
// plane at the default 54 x 32 grid (0.012 at the coarsest grids the loader allows) and still below
// the lid opening.
constexpr glm::dvec3 kCandleOffset{0.05, -0.28, 0.11};

}  // namespace

void addPumpkins(Scene& scene, const PumpkinOptions& o) {
  SceneBuilder b(scene);
  const int wood = b.material(material("porch_wood", {0.45, 0.3, 0.2}, glm::dvec3(0.1), 16.0));
  const int wall = b.material(material("porch_wall", {0.7, 0.68, 0.62}));
  const int door = b.material(material("door", {0.35, 0.12, 0.08}, glm::dvec3(0.2), 32.0));
  const int ground = b.material(material("ground", {0.25, 0.3, 0.2}));
  const int orange = b.material(material("pumpkin", {0.95, 0.45, 0.05}, glm::dvec3(0.3), 24.0));
  const int stemMaterial = b.material(material("stem", {0.3, 0.35, 0.12}));

  Node porch = SceneBuilder::group("pumpkins");
  auto box = [&](const std::string& name, glm::dvec3 lo, glm::dvec3 hi, int mat) {
    porch.children.push_back(SceneBuilder::node(name, b.mesh(makeBoxBetween(lo, hi), name), mat));
  };
  // The porch: floor (top at y = 0), back wall with a door, a roof on two posts, two steps down to
  // the ground in front.
  box("ground", {-15.0, -0.8, -6.0}, {15.0, -0.6, 15.0}, ground);
  box("floor", {-4.0, -0.6, -3.3}, {4.0, 0.0, 3.0}, wood);
  box("step_upper", {-1.2, -0.3, 3.0}, {1.2, -0.1, 3.35}, wood);
  box("step_lower", {-1.2, -0.6, 3.0}, {1.2, -0.3, 3.7}, wood);
  box("back_wall", {-4.0, 0.0, -3.3}, {4.0, 3.0, -3.0}, wall);
  box("door", {-0.6, 0.0, -3.0}, {0.6, 2.2, -2.94}, door);
  box("post_west", {-3.85, 0.0, 2.6}, {-3.6, 3.0, 2.85}, wood);
  box("post_east", {3.6, 0.0, 2.6}, {3.85, 3.0, 2.85}, wood);
  box("roof", {-4.2, 3.0, -3.3}, {4.2, 3.2, 3.1}, wood);

  const int stemMesh = b.mesh(makeCylinder(0.035, 0.16, 10), "pumpkin_stem");
  glm::dvec3 candlePosition(0.0);
  for (int i = 0; i < 7; ++i) {
    const PumpkinPlace& p = kPumpkins[i];
    PumpkinShape shape;
    shape.radius = p.radius;
    shape.slices = o.slices;
    shape.stacks = o.stacks;
    const bool lantern = i == 0;
    Mesh mesh = lantern ? makeHollowPumpkin(shape, 0.04) : makePumpkin(shape);
    const double lift = -mesh.bounds.min.y;  // rest on the floor
    const double top = mesh.bounds.max.y;
    const std::string name = lantern ? "lantern" : "pumpkin" + std::to_string(i);
    const glm::dvec3 centre(p.x, lift, p.z);
    const glm::dmat4 place = translation(centre) * rotationY(p.turnDegrees * kDegrees);
    Node node = SceneBuilder::node(name, b.mesh(std::move(mesh), name), orange, place);
    if (lantern) {
      candlePosition = glm::dvec3(place * glm::dvec4(kCandleOffset * p.radius, 1.0));
    } else {
      // The stem stands in the dimple around the top.
      node.children.push_back(SceneBuilder::node("stem", stemMesh, stemMaterial, translation({0.0, top + 0.05, 0.0})));
    }
    porch.children.push_back(std::move(node));
  }
  b.root(std::move(porch));

  Light candle;
  candle.name = "candle";
  candle.type = LightType::Point;
  candle.position = candlePosition;
  candle.color = {1.0, 0.75, 0.4};
  scene.lights.push_back(candle);

  if (o.setView) {
    scene.width = 800;
    scene.height = 640;
    scene.ambient = glm::dvec3(0.1);
    // 42 degrees left of the lantern's face, outside every opening: its shell lies between the
    // candle and the eye, so the camera is inside the lantern's shadow volume
    // ([Kuhn 2016, Fig. 5.8]) and z-pass miscounts, while the face still shows.
    scene.camera.eye = {-1.4, 1.1, 3.1};
    scene.camera.target = {0.4, 0.35, 1.0};
    scene.camera.up = {0.0, 1.0, 0.0};
    scene.camera.fovYDegrees = 55.0;
    scene.camera.nearPlane = 0.05;
    scene.camera.farPlane = kInfinity;
  }
}

}  // namespace shadowref
