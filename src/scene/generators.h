// The documents' test scenes as generators: each adds its meshes, materials,
// one root node, its lights and — when `setView` is on — the camera, image size and ambient light
// into a Scene. Seeded and deterministic: the same options give bit-identical scenes everywhere.
#pragma once

#include <cstdint>

#include "scene/scene.h"

namespace shadowref {

// [Kuhn 2016, Fig. 5.1]: a closed room seen from inside (floor, ceiling and four walls as separate
// slabs), a table and two chairs, a point light just under the centre of the ceiling. 800 x 640.
struct RoomOptions {
  glm::dvec3 size{8.0, 3.0, 6.0};  // inside dimensions (x, y, z); the floor's top is y = 0
  double wallThickness = 0.2;
  bool setView = true;
};
void addRoom(Scene& scene, const RoomOptions& options = {});

// The default scene of `shadowref render` without a scene file: the room.
Scene makeDefaultScene();

// [Kuhn 2016, Fig. 5.2 and 5.8]: a porch with seven pumpkins; one is hollow, with openings for its
// face and its lid, and holds the point light. The default camera sits in the shell's shadow
// volume, so z-pass counts wrongly there. About 27 000 triangles, as in the document.
struct PumpkinOptions {
  int slices = 54;  // around each pumpkin
  int stacks = 32;  // pole to pole
  bool setView = true;
};
void addPumpkins(Scene& scene, const PumpkinOptions& options = {});

// [Kuhn 2016, §5.4.1]: blocks of four houses on a ground slab; each house one of a few simple
// closed models, chosen at random or always `model`; one point light high above, or `lights` in a
// grid.
struct CityOptions {
  int houses = 64;
  bool randomModels = true;
  int model = 0;  // the model of every house when !randomModels (0 .. kCityModelCount-1)
  uint32_t seed = 1;
  int lights = 1;
  // The camera, the lights and the ground as for a city of this many houses (at least `houses`;
  // 0: `houses`), so that a series over the number of houses changes only the houses.
  int framedHouses = 0;
  bool setView = true;
};
inline constexpr int kCityModelCount = 4;
void addCity(Scene& scene, const CityOptions& options = {});

// [Hempe 2004, §6]: a wide terrain with gentle hills, trees and poles under a low directional light
// — the shadow-map scene (finite far plane, so the camera frustum has eight corners for TSM).
struct OutdoorOptions {
  uint32_t seed = 1;
  int trees = 40;
  int poles = 12;
  double size = 400.0;  // side of the square ground
  bool setView = true;
};
void addOutdoor(Scene& scene, const OutdoorOptions& options = {});

}  // namespace shadowref
