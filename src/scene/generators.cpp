// The room of [Kuhn 2016, Fig. 5.1] and the default scene. The other generators:
// generator_pumpkins.cpp, generator_city.cpp, generator_outdoor.cpp.
#include "scene/generators.h"

#include "scene/generator_support.h"
#include "scene/primitives.h"

namespace shadowref {

using namespace generator;

namespace {

// A table: a top on four legs, its origin on the floor under the top's centre.
Node makeTable(SceneBuilder& b, int wood) {
  const double topY = 0.72, topThickness = 0.05, halfX = 0.8, halfZ = 0.45, leg = 0.07, inset = 0.06;
  Node table = SceneBuilder::group("table");
  table.children.push_back(SceneBuilder::node(
      "top", b.mesh(makeBoxBetween({-halfX, topY, -halfZ}, {halfX, topY + topThickness, halfZ}), "table_top"), wood));
  const int legMesh = b.mesh(makeBoxBetween({-leg / 2, 0.0, -leg / 2}, {leg / 2, topY, leg / 2}), "table_leg");
  const double lx = halfX - inset - leg / 2, lz = halfZ - inset - leg / 2;
  const glm::dvec3 corners[4] = {{-lx, 0, -lz}, {lx, 0, -lz}, {-lx, 0, lz}, {lx, 0, lz}};
  for (int i = 0; i < 4; ++i)
    table.children.push_back(SceneBuilder::node("leg" + std::to_string(i), legMesh, wood, translation(corners[i])));
  return table;
}

// A chair facing +x (its back at -x): seat, back rest and four legs; origin on the floor under the
// seat's centre. The meshes are shared by every chair.
struct ChairMeshes {
  int seat, back, leg;
};

ChairMeshes makeChairMeshes(SceneBuilder& b) {
  const double half = 0.22, seatY = 0.45, seatThickness = 0.04, leg = 0.04;
  return {b.mesh(makeBoxBetween({-half, seatY, -half}, {half, seatY + seatThickness, half}), "chair_seat"),
          b.mesh(makeBoxBetween({-half, seatY + seatThickness, -half}, {-half + 0.04, 1.0, half}), "chair_back"),
          b.mesh(makeBoxBetween({-leg / 2, 0.0, -leg / 2}, {leg / 2, seatY, leg / 2}), "chair_leg")};
}

Node makeChair(const ChairMeshes& m, int material, const std::string& name, const glm::dmat4& place) {
  Node chair = SceneBuilder::group(name, place);
  chair.children.push_back(SceneBuilder::node("seat", m.seat, material));
  chair.children.push_back(SceneBuilder::node("back", m.back, material));
  const double l = 0.22 - 0.02;
  const glm::dvec3 corners[4] = {{-l, 0, -l}, {l, 0, -l}, {-l, 0, l}, {l, 0, l}};
  for (int i = 0; i < 4; ++i)
    chair.children.push_back(SceneBuilder::node("leg" + std::to_string(i), m.leg, material, translation(corners[i])));
  return chair;
}

}  // namespace

void addRoom(Scene& scene, const RoomOptions& o) {
  SceneBuilder b(scene);
  const int wallMaterial = b.material(material("wall", {0.8, 0.78, 0.72}));
  const int floorMaterial = b.material(material("floor", {0.55, 0.42, 0.3}, glm::dvec3(0.2), 24.0));
  const int wood = b.material(material("wood", {0.6, 0.36, 0.18}, glm::dvec3(0.3), 32.0));
  const int chairMaterial = b.material(material("chair", {0.3, 0.45, 0.6}, glm::dvec3(0.2), 16.0));

  // Inside: x in [-X, X], y in [0, H], z in [-Z, Z]. Six slabs, each a closed box, that meet at the
  // room's edges; together they close the room so no light leaks and the camera sits inside.
  const double X = 0.5 * o.size.x, H = o.size.y, Z = 0.5 * o.size.z, t = o.wallThickness;
  Node room = SceneBuilder::group("room");
  auto slab = [&](const std::string& name, glm::dvec3 lo, glm::dvec3 hi, int mat) {
    room.children.push_back(SceneBuilder::node(name, b.mesh(makeBoxBetween(lo, hi), name), mat));
  };
  slab("floor", {-X - t, -t, -Z - t}, {X + t, 0.0, Z + t}, floorMaterial);
  slab("ceiling", {-X - t, H, -Z - t}, {X + t, H + t, Z + t}, wallMaterial);
  slab("wall_west", {-X - t, 0.0, -Z}, {-X, H, Z}, wallMaterial);
  slab("wall_east", {X, 0.0, -Z}, {X + t, H, Z}, wallMaterial);
  slab("wall_north", {-X - t, 0.0, -Z - t}, {X + t, H, -Z}, wallMaterial);
  slab("wall_south", {-X - t, 0.0, Z}, {X + t, H, Z + t}, wallMaterial);

  room.children.push_back(makeTable(b, wood));
  const ChairMeshes chair = makeChairMeshes(b);
  room.children.push_back(makeChair(chair, chairMaterial, "chair0", translation({-1.15, 0.0, 0.1})));
  room.children.push_back(
      makeChair(chair, chairMaterial, "chair1", translation({1.1, 0.0, -0.15}) * quarterTurnsY(2)));
  b.root(std::move(room));

  // [Kuhn 2016, §5.2]:
  // "eine Punktlichtquelle, welche sich direkt mittig unter der Decke des Raumes befindet".
  Light light;
  light.name = "ceiling";
  light.type = LightType::Point;
  light.position = {0.0, H - 0.05, 0.0};
  light.color = glm::dvec3(1.0);
  scene.lights.push_back(light);

  if (o.setView) {
    scene.width = 800;
    scene.height = 640;
    scene.ambient = glm::dvec3(0.15);
    scene.camera.eye = {0.8 * X, 0.65 * H, 0.85 * Z};
    scene.camera.target = {0.0, 0.5, 0.0};
    scene.camera.up = {0.0, 1.0, 0.0};
    scene.camera.fovYDegrees = 60.0;
    scene.camera.nearPlane = 0.1;
    scene.camera.farPlane = kInfinity;
  }
}

Scene makeDefaultScene() {
  Scene scene;
  scene.sourceFile = "<builtin:room>";
  addRoom(scene);
  return scene;
}

}  // namespace shadowref
