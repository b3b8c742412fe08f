#include <functional>
#include <set>

#include <catch2/catch.hpp>

#include "scene/generators.h"
#include "scene/pumpkin.h"
#include "mesh_checks.h"

using namespace shadowref;

namespace {

// Every mesh of the scene is a closed, outward-wound 2-manifold; the lantern has genus 3.
void requireAllMeshesClosed(const Scene& scene) {
  for (const auto& mesh : scene.meshes)
    shadowref::testing::requireClosedOutward(*mesh, mesh->name == "lantern" ? kLanternOpenings - 1 : 0);
}

size_t countNodes(const std::vector<Node>& nodes, const std::function<bool(const Node&)>& pred) {
  size_t n = 0;
  for (const Node& node : nodes) n += (pred(node) ? 1 : 0) + countNodes(node.children, pred);
  return n;
}

bool startsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

size_t triangleCount(const Scene& scene) {
  size_t n = 0;
  for (const Instance& i : scene.instances()) n += i.mesh->weldedTriangles.size();
  return n;
}

// Möller–Trumbore: does the open segment p -> q cross triangle (a, b, c)?
bool segmentHitsTriangle(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& a, const glm::dvec3& b,
                         const glm::dvec3& c) {
  const glm::dvec3 d = q - p, e1 = b - a, e2 = c - a;
  const glm::dvec3 h = glm::cross(d, e2);
  const double det = glm::dot(e1, h);
  if (std::abs(det) < 1e-15) return false;
  const glm::dvec3 s = p - a;
  const double u = glm::dot(s, h) / det;
  if (u < 0.0 || u > 1.0) return false;
  const glm::dvec3 qv = glm::cross(s, e1);
  const double v = glm::dot(d, qv) / det;
  if (v < 0.0 || u + v > 1.0) return false;
  const double t = glm::dot(e2, qv) / det;
  return t > 1e-9 && t < 1.0 - 1e-9;
}

// Number of shadow-casting triangles between a point light and a point: > 0 means the point lies
// inside a shadow volume of that light.
int occludersBetween(const Scene& scene, const glm::dvec3& light, const glm::dvec3& eye) {
  int hits = 0;
  for (const Instance& inst : scene.instances()) {
    if (!inst.shadowMesh) continue;
    const Mesh& m = *inst.shadowMesh;
    for (const glm::uvec3& t : m.weldedTriangles) {
      glm::dvec3 w[3];
      for (int i = 0; i < 3; ++i) w[i] = glm::dvec3(inst.world * glm::dvec4(m.weldedPositions[t[i]], 1.0));
      hits += segmentHitsTriangle(light, eye, w[0], w[1], w[2]);
    }
  }
  return hits;
}

bool inside(const Aabb& box, const glm::dvec3& p) {
  return glm::all(glm::lessThan(box.min, p)) && glm::all(glm::lessThan(p, box.max));
}

std::vector<glm::dmat4> worldMatrices(const Scene& scene) {
  std::vector<glm::dmat4> out;
  for (const Instance& i : scene.instances()) out.push_back(i.world);
  return out;
}

std::vector<glm::dvec3> allPositions(const Scene& scene) {
  std::vector<glm::dvec3> out;
  for (const auto& m : scene.meshes) out.insert(out.end(), m->weldedPositions.begin(), m->weldedPositions.end());
  return out;
}

}  // namespace

TEST_CASE("the lantern is one closed shell of genus 3: V-E+F = -4 with four openings", "[mesh]") {
  const Mesh lantern = makeHollowPumpkin(PumpkinShape{}, 0.04);
  shadowref::testing::requireClosedOutward(lantern, /*genus=*/3);
  CHECK(shadowref::testing::componentCount(lantern) == 1);
  CHECK(shadowref::testing::eulerCharacteristic(lantern) == -4);
  // Shell volume: less than the solid pumpkin, more than nothing.
  CHECK(signedVolume(lantern) < signedVolume(makePumpkin(PumpkinShape{})) * 0.5);
}

TEST_CASE("a solid pumpkin is a closed genus-0 surface", "[mesh]") {
  shadowref::testing::requireClosedOutward(makePumpkin(PumpkinShape{}));
}

TEST_CASE("room: closed slabs, table, two chairs, light just under the ceiling centre, camera inside", "[mesh]") {
  Scene scene;
  addRoom(scene);
  requireAllMeshesClosed(scene);
  REQUIRE(scene.lights.size() == 1);
  const Light& light = scene.lights[0];
  CHECK(light.type == LightType::Point);
  CHECK(light.position.x == 0.0);
  CHECK(light.position.z == 0.0);
  CHECK(light.position.y < 3.0);
  CHECK(light.position.y > 2.8);
  CHECK(countNodes(scene.roots, [](const Node& n) { return n.name == "table"; }) == 1);
  CHECK(countNodes(scene.roots, [](const Node& n) { return startsWith(n.name, "chair"); }) == 2);
  // Camera and light inside the room: nothing between them and the room's inside.
  const glm::dvec3 eye = scene.camera.eye;
  CHECK(std::abs(eye.x) < 4.0);
  CHECK(std::abs(eye.z) < 3.0);
  CHECK(eye.y > 0.0);
  CHECK(eye.y < 3.0);
  CHECK(occludersBetween(scene, light.position, eye) == 0);
  // The table shadows the floor under it.
  CHECK(occludersBetween(scene, light.position, {0.0, 0.001, 0.0}) > 0);
}

TEST_CASE("the default scene is the room at 800 x 640", "[mesh]") {
  const Scene scene = makeDefaultScene();
  CHECK(scene.width == 800);
  CHECK(scene.height == 640);
  CHECK(scene.sourceFile == "<builtin:room>");
  CHECK(scene.roots.size() == 1);
  CHECK(scene.roots[0].name == "room");
}

TEST_CASE("pumpkins: seven pumpkins, the light inside the lantern, the camera in its shadow", "[mesh]") {
  Scene scene;
  addPumpkins(scene);
  requireAllMeshesClosed(scene);
  CHECK(countNodes(scene.roots, [](const Node& n) { return startsWith(n.name, "pumpkin") || n.name == "lantern"; }) == 8);
  REQUIRE(scene.lights.size() == 1);
  const glm::dvec3 light = scene.lights[0].position;
  const Instance* lantern = nullptr;
  const auto instances = scene.instances();
  for (const Instance& i : instances)
    if (i.mesh->name == "lantern") lantern = &i;
  REQUIRE(lantern != nullptr);
  CHECK(inside(lantern->worldBounds, light));
  // [Kuhn 2016, Fig. 5.8]: the eye lies in a shadow volume — the lantern's shell is between it and
  // the light.
  CHECK(occludersBetween(scene, light, scene.camera.eye) > 0);
  // The light escapes: straight up through the lid and out through the face.
  CHECK(occludersBetween(scene, light, light + glm::dvec3(0.0, 2.5, 0.0)) == 0);
  const size_t triangles = triangleCount(scene);
  CHECK(triangles > 24000);
  CHECK(triangles < 30000);
}

TEST_CASE("pumpkins node list: the group root holds 7 pumpkin nodes", "[mesh]") {
  Scene scene;
  addPumpkins(scene);
  size_t pumpkins = 0;
  for (const Node& n : scene.roots.at(0).children) pumpkins += startsWith(n.name, "pumpkin") || n.name == "lantern";
  CHECK(pumpkins == 7);
}

TEST_CASE("city(houses = N) has exactly N houses in blocks of four", "[mesh]") {
  for (int houses : {1, 4, 5, 16, 64, 100}) {
    Scene scene;
    CityOptions o;
    o.houses = houses;
    addCity(scene, o);
    INFO("houses " << houses);
    CHECK(countNodes(scene.roots, [](const Node& n) { return startsWith(n.name, "house"); }) == size_t(houses));
    CHECK(countNodes(scene.roots, [](const Node& n) { return startsWith(n.name, "block"); }) == size_t((houses + 3) / 4));
  }
}

TEST_CASE("city meshes are closed and every house stands on the ground", "[mesh]") {
  Scene scene;
  addCity(scene, CityOptions{});
  requireAllMeshesClosed(scene);
  for (const Instance& i : scene.instances()) {
    INFO(i.path);
    if (i.path == "city/ground") CHECK(i.worldBounds.max.y == 0.0);
    else CHECK(i.worldBounds.min.y >= 0.0);
  }
}

TEST_CASE("city is deterministic per seed, another seed or single model changes it", "[mesh]") {
  auto build = [](CityOptions o) {
    Scene s;
    addCity(s, o);
    return s;
  };
  CityOptions o;
  const Scene a = build(o), b = build(o);
  CHECK(worldMatrices(a) == worldMatrices(b));
  CHECK(allPositions(a) == allPositions(b));
  o.seed = 2;
  CHECK(worldMatrices(build(o)) != worldMatrices(a));
  // One model repeated: every house has the same parts.
  o.randomModels = false;
  o.model = 0;
  const Scene single = build(o);
  std::set<int> meshes;
  for (const Node& block : single.roots[0].children)
    for (const Node& house : block.children)
      for (const Node& part : house.children) meshes.insert(part.mesh);
  CHECK(meshes.size() == 2);  // body and roof of Haus01
}

TEST_CASE("city with several lights places them all above the city, sharing the intensity", "[mesh]") {
  Scene scene;
  CityOptions o;
  o.houses = 16;
  o.lights = 9;
  addCity(scene, o);
  REQUIRE(scene.lights.size() == 9);
  std::set<std::pair<double, double>> spots;
  for (const Light& l : scene.lights) {
    CHECK(l.position.y > 20.0);
    CHECK(l.color.x == Approx(1.0 / 9.0));
    spots.insert({l.position.x, l.position.z});
  }
  CHECK(spots.size() == 9);
}

TEST_CASE("city framed for more houses: the houses of its own count, the view, lights and ground of the larger city", "[mesh]") {
  auto build = [](int houses, int framed) {
    Scene s;
    CityOptions o;
    o.houses = houses;
    o.framedHouses = framed;
    o.lights = 4;
    addCity(s, o);
    return s;
  };
  auto ground = [](const Scene& s) { return s.instances().front().worldBounds; };
  auto housesOnly = [](const Scene& s) {
    std::vector<Instance> out;
    for (const Instance& i : s.instances())
      if (i.path != "city/ground") out.push_back(i);
    return out;
  };
  const Scene small = build(8, 0), framed = build(8, 100), large = build(100, 0);
  REQUIRE(framed.instances().front().path == "city/ground");
  // The camera, the lights and the ground are those made for 100 houses ...
  CHECK(framed.camera.eye == large.camera.eye);
  CHECK(framed.camera.target == large.camera.target);
  REQUIRE(framed.lights.size() == large.lights.size());
  for (size_t i = 0; i < framed.lights.size(); ++i) CHECK(framed.lights[i].position == large.lights[i].position);
  CHECK(ground(framed).min == ground(large).min);
  CHECK(ground(framed).max == ground(large).max);
  CHECK(framed.camera.eye != small.camera.eye);
  // ... the houses those of 8: the same models at the same places.
  const std::vector<Instance> a = housesOnly(framed), b = housesOnly(small);
  REQUIRE(a.size() == b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    CHECK(a[i].path == b[i].path);
    CHECK(a[i].mesh->name == b[i].mesh->name);
    CHECK(a[i].world == b[i].world);
  }
  // Framed for as many houses or fewer: the city as without it.
  for (int f : {8, 4, 1}) {
    const Scene same = build(8, f);
    CHECK(same.camera.eye == small.camera.eye);
    CHECK(same.lights[0].position == small.lights[0].position);
    CHECK(ground(same).max == ground(small).max);
  }
}

TEST_CASE("outdoor: closed meshes, N trees, low directional light, finite far plane", "[mesh]") {
  Scene scene;
  OutdoorOptions o;
  o.trees = 25;
  addOutdoor(scene, o);
  requireAllMeshesClosed(scene);
  CHECK(countNodes(scene.roots, [](const Node& n) { return startsWith(n.name, "tree"); }) == 25);
  REQUIRE(scene.lights.size() == 1);
  const Light& sun = scene.lights[0];
  CHECK(sun.type == LightType::Directional);
  const double elevation = std::asin(-sun.direction.y) * 180.0 / 3.14159265358979323846;
  CHECK(elevation > 10.0);
  CHECK(elevation < 45.0);
  CHECK(std::isfinite(scene.camera.farPlane));
}

TEST_CASE("outdoor is deterministic per seed", "[mesh]") {
  Scene a, b, c;
  addOutdoor(a, OutdoorOptions{});
  addOutdoor(b, OutdoorOptions{});
  OutdoorOptions other;
  other.seed = 7;
  addOutdoor(c, other);
  CHECK(worldMatrices(a) == worldMatrices(b));
  CHECK(allPositions(a) == allPositions(b));
  CHECK(worldMatrices(a) != worldMatrices(c));
}

TEST_CASE("generators add to a scene without disturbing what is there", "[mesh]") {
  Scene scene;
  addRoom(scene);
  const size_t meshes = scene.meshes.size(), materials = scene.materials.size();
  CityOptions o;
  o.houses = 4;
  o.setView = false;
  const Camera before = scene.camera;
  addCity(scene, o);
  CHECK(scene.roots.size() == 2);
  CHECK(scene.meshes.size() > meshes);
  CHECK(scene.materials.size() > materials);
  CHECK(scene.camera.eye == before.eye);
  // Material indices of the room still name the room's materials.
  CHECK(scene.materials[scene.roots[0].children[0].material].name == "floor");
}

TEST_CASE("the lantern stays a closed genus-3 shell at every grid resolution the loader allows", "[mesh]") {
  for (auto [slices, stacks] : {std::pair{18, 16}, std::pair{24, 20}, std::pair{54, 32}, std::pair{101, 64}}) {
    INFO(slices << " x " << stacks);
    PumpkinShape shape;
    shape.slices = slices;
    shape.stacks = stacks;
    shadowref::testing::requireClosedOutward(makeHollowPumpkin(shape, 0.04), /*genus=*/3);
  }
}
