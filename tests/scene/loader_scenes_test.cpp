// Every scene shipped in scenes/ loads, and holds something to draw and light.
#include <algorithm>
#include <filesystem>

#include <catch2/catch.hpp>

#include "scene/scene_loader.h"

using namespace shadowref;

namespace {
std::vector<std::string> shippedScenes() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(SHADOWREF_SOURCE_DIR) + "/scenes"))
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  return files;
}
}  // namespace

TEST_CASE("every scene in scenes/ loads with instances, lights and triangles", "[loader]") {
  const std::vector<std::string> files = shippedScenes();
  REQUIRE(files.size() >= 10);
  for (const std::string& file : files) {
    INFO(file);
    Scene scene;
    try {
      scene = loadScene(file);
    } catch (const SceneError& e) {
      FAIL(e.what());
    }
    const std::vector<Instance> instances = scene.instances();
    CHECK(!instances.empty());
    CHECK(!scene.lights.empty());
    size_t triangles = 0;
    for (const Instance& i : instances) triangles += i.mesh->triangles.size();
    CHECK(triangles > 0);
    CHECK(scene.sourceFile == file);
  }
}

TEST_CASE("city.yaml has 64 houses and city16.yaml 16 of one model", "[loader]") {
  const std::string dir = std::string(SHADOWREF_SOURCE_DIR) + "/scenes/";
  auto countHouses = [](const Scene& s) {
    size_t n = 0;
    for (const Instance& i : s.instances())
      if (i.path.find("house") != std::string::npos) ++n;
    return n;
  };
  const Scene city = loadScene(dir + "city.yaml");
  const Scene city16 = loadScene(dir + "city16.yaml");
  CHECK(countHouses(city) > 0);
  CHECK(countHouses(city16) > 0);
  CHECK(countHouses(city) == 4 * countHouses(city16));
}

TEST_CASE("obj_example.yaml reads the house OBJ relative to the scene file and welds it closed", "[loader]") {
  const Scene scene = loadScene(std::string(SHADOWREF_SOURCE_DIR) + "/scenes/obj_example.yaml");
  const Mesh* house = nullptr;
  for (const auto& m : scene.meshes)
    if (m->name == "house") house = m.get();
  REQUIRE(house != nullptr);
  // 2 pentagons (3 triangles each) + 5 quads (2 each); 10 corners after welding the split vertices.
  CHECK(house->triangles.size() == 16);
  CHECK(house->weldedPositions.size() == 10);
  CHECK(house->topology == Topology::Closed);
  CHECK(house->edges.size() == 24);  // Euler: V - E + F = 10 - 24 + 16 = 2
}
