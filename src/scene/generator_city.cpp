// The urban scene of [Kuhn 2016, §5.4.1]:
// "Ein Block besteht dabei aus vier zufällig ausgewählten Häusern. Bei den Häusern handelt es sich um sehr einfache, polygonarme Modelle."
#include <algorithm>
#include <array>
#include <cmath>

#include "scene/generator_support.h"
#include "scene/generators.h"
#include "scene/primitives.h"

namespace shadowref {

using namespace generator;

namespace {

// Maps a prism extruded along y (primitives.h) onto one lying along z with its cross-section in the
// xy plane: (x, y, z) -> (x, z, -y). Exact: every entry is 0 or ±1.
glm::dmat4 lieAlongZ() {
  glm::dmat4 m(0.0);
  m[0] = {1, 0, 0, 0};   // x -> x
  m[1] = {0, 0, -1, 0};  // y -> -z
  m[2] = {0, 1, 0, 0};   // z -> y
  m[3] = {0, 0, 0, 1};
  return m;
}

struct CityMaterials {
  int walls[3];
  int roof, ground;
};

// One house model: its meshes (made once, shared by every house that uses the model) and how to
// place them. Every part is its own closed mesh; parts touch but never need to be joined.
struct HouseModel {
  std::vector<std::pair<int, glm::dmat4>> parts;  // mesh, placement in the house
  std::vector<bool> isRoof;
};

std::array<HouseModel, kCityModelCount> makeHouseModels(SceneBuilder& b) {
  std::array<HouseModel, kCityModelCount> models;
  auto add = [&](HouseModel& h, Mesh mesh, const std::string& name, const glm::dmat4& place, bool roof) {
    h.parts.emplace_back(b.mesh(std::move(mesh), name), place);
    h.isRoof.push_back(roof);
  };
  // Haus01: a box with a gable roof.
  add(models[0], makeBoxBetween({-4.0, 0.0, -3.0}, {4.0, 5.0, 3.0}), "house01_body", glm::dmat4(1.0), false);
  add(models[0], makeExtrudedPolygon({{-4.4, 0.0}, {4.4, 0.0}, {0.0, 3.0}}, 6.6), "house01_roof",
      translation({0.0, 5.0, 0.0}) * lieAlongZ(), true);
  // Haus02: a flat-roofed block with a chimney.
  add(models[1], makeBoxBetween({-3.5, 0.0, -3.5}, {3.5, 7.0, 3.5}), "house02_body", glm::dmat4(1.0), false);
  add(models[1], makeBoxBetween({1.5, 7.0, 1.5}, {2.3, 8.5, 2.3}), "house02_chimney", glm::dmat4(1.0), true);
  // An L-shaped house: two wings of different height.
  add(models[2], makeBoxBetween({-4.5, 0.0, -4.5}, {4.5, 4.0, -1.0}), "house_l_wing_a", glm::dmat4(1.0), false);
  add(models[2], makeBoxBetween({-4.5, 0.0, -1.0}, {-1.0, 6.0, 4.5}), "house_l_wing_b", glm::dmat4(1.0), false);
  // A tower: a cylinder under a cone.
  add(models[3], makeCylinder(2.5, 10.0, 16), "tower_body", translation({0.0, 5.0, 0.0}), false);
  add(models[3], makeCone(3.0, 3.0, 16), "tower_roof", translation({0.0, 11.5, 0.0}), true);
  return models;
}

constexpr double kLot = 12.0, kBlockPitch = 2.0 * kLot + 12.0;

// The square grid of blocks that holds `houses`, and its extent.
struct BlockGrid {
  int blocks = 0, perRow = 1;
  double extentX = 0.0, extentZ = 0.0;
};

BlockGrid blockGrid(int houses) {
  BlockGrid g;
  g.blocks = (houses + 3) / 4;
  g.perRow = std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(g.blocks)))));
  const int rows = (g.blocks + g.perRow - 1) / g.perRow;
  g.extentX = g.perRow * kBlockPitch;
  g.extentZ = std::max(1, rows) * kBlockPitch;
  return g;
}

}  // namespace

void addCity(Scene& scene, const CityOptions& o) {
  SceneBuilder b(scene);
  SeededRandom random(o.seed);
  CityMaterials mat{};
  mat.walls[0] = b.material(material("plaster", {0.85, 0.8, 0.7}));
  mat.walls[1] = b.material(material("brick", {0.65, 0.3, 0.22}));
  mat.walls[2] = b.material(material("stone", {0.6, 0.62, 0.65}));
  mat.roof = b.material(material("roof", {0.45, 0.15, 0.12}, glm::dvec3(0.2), 16.0));
  mat.ground = b.material(material("asphalt", {0.35, 0.35, 0.37}));
  const std::array<HouseModel, kCityModelCount> models = makeHouseModels(b);

  // Blocks of 2 x 2 lots, the blocks on a square grid with streets between them, centred on the
  // origin; the ground, the camera and the lights are placed for the grid of framedHouses.
  const int houses = std::max(0, o.houses);
  const BlockGrid grid = blockGrid(houses);
  const BlockGrid framed = blockGrid(std::max(houses, o.framedHouses));
  const int blocks = grid.blocks, perRow = grid.perRow;
  const double extentX = grid.extentX, extentZ = grid.extentZ;

  Node city = SceneBuilder::group("city");
  city.children.push_back(SceneBuilder::node(
      "ground",
      b.mesh(makePlane({framed.extentX + 2.0 * kLot, framed.extentZ + 2.0 * kLot}, 0.5), "city_ground"), mat.ground));
  for (int k = 0; k < blocks; ++k) {
    const glm::dvec3 blockCentre((k % perRow + 0.5) * kBlockPitch - 0.5 * extentX, 0.0,
                                 (k / perRow + 0.5) * kBlockPitch - 0.5 * extentZ);
    Node block = SceneBuilder::group("block" + std::to_string(k), translation(blockCentre));
    for (int h = 0; h < 4 && 4 * k + h < houses; ++h) {
      const int index = 4 * k + h;
      const int model = o.randomModels ? random.below(kCityModelCount)
                                       : std::clamp(o.model, 0, kCityModelCount - 1);
      const int turns = o.randomModels ? random.below(4) : 0;
      const int wall = o.randomModels ? random.below(3) : 0;
      const glm::dvec3 lotCentre((h % 2 - 0.5) * kLot, 0.0, (h / 2 - 0.5) * kLot);
      Node house = SceneBuilder::group("house" + std::to_string(index), translation(lotCentre) * quarterTurnsY(turns));
      const HouseModel& m = models[model];
      for (size_t p = 0; p < m.parts.size(); ++p)
        house.children.push_back(SceneBuilder::node(m.isRoof[p] ? "roof" + std::to_string(p) : "body" + std::to_string(p),
                                                    m.parts[p].first, m.isRoof[p] ? mat.roof : mat.walls[wall],
                                                    m.parts[p].second));
      block.children.push_back(std::move(house));
    }
    city.children.push_back(std::move(block));
  }
  b.root(std::move(city));

  // One light high above the centre, or several on a square grid above the city
  // ([Kuhn 2016, §5.4.1], the second test adds lights), their intensities sharing 1 so the picture
  // keeps its brightness.
  const int lights = std::max(1, o.lights);
  const int lightsPerRow = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(lights))));
  const double span = 0.5 * std::max(framed.extentX, framed.extentZ);
  const double height = 40.0 + span;
  for (int i = 0; i < lights; ++i) {
    Light light;
    light.name = "sun" + std::to_string(i);
    light.type = LightType::Point;
    const double u = lightsPerRow == 1 ? 0.0 : (i % lightsPerRow) / double(lightsPerRow - 1) - 0.5;
    const double v = lightsPerRow == 1 ? 0.0 : (i / lightsPerRow) / double(lightsPerRow - 1) - 0.5;
    light.position = {0.3 * span + u * span, height, 0.2 * span + v * span};
    light.color = glm::dvec3(1.0 / lights);
    scene.lights.push_back(light);
  }

  if (o.setView) {
    scene.width = 800;
    scene.height = 640;
    scene.ambient = glm::dvec3(0.2);
    const double r = span;
    scene.camera.eye = {-0.9 * r - 10.0, 0.6 * r + 12.0, 1.3 * r + 15.0};
    scene.camera.target = {0.0, 0.0, 0.0};
    scene.camera.up = {0.0, 1.0, 0.0};
    scene.camera.fovYDegrees = 50.0;
    scene.camera.nearPlane = 0.5;
    scene.camera.farPlane = kInfinity;
  }
}

}  // namespace shadowref
