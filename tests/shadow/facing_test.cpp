#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/primitives.h"
#include "shadow/facing.h"
#include "volume_fixtures.h"

using namespace shadowref;

namespace {

// The triangles of a unit box (corners at ±1) whose outward normal is `normal`.
std::vector<uint8_t> trianglesWithNormal(const Mesh& box, const glm::dvec3& normal) {
  std::vector<uint8_t> out;
  for (const glm::dvec3& n : box.faceNormals) out.push_back(glm::dot(n, normal) > 0.99 ? 1 : 0);
  return out;
}

}  // namespace

TEST_CASE("facing: a point light beside one face of a box lights exactly that face", "[volumes][facing]") {
  const Mesh box = makeBox({2.0, 2.0, 2.0});
  for (const glm::dvec3 axis : {glm::dvec3(1, 0, 0), glm::dvec3(-1, 0, 0), glm::dvec3(0, 1, 0),
                                glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1)}) {
    INFO("light on axis " << axis.x << "," << axis.y << "," << axis.z);
    std::vector<uint8_t> facing;
    computeFacing(box, glm::dvec4(5.0 * axis, 1.0), facing);
    CHECK(facing == trianglesWithNormal(box, axis));
    CHECK(std::count(facing.begin(), facing.end(), 1) == 2);
  }
}

TEST_CASE("facing: a directional light (towards-light vector, w = 0) lights the faces with N·L > 0",
          "[volumes][facing]") {
  const Mesh box = makeBox({2.0, 2.0, 2.0});
  std::vector<uint8_t> facing;
  computeFacing(box, glm::dvec4(0.0, 0.0, 1.0, 0.0), facing);
  CHECK(facing == trianglesWithNormal(box, {0, 0, 1}));
  // From a corner direction three faces, six triangles.
  computeFacing(box, glm::dvec4(glm::normalize(glm::dvec3(1, 1, 1)), 0.0), facing);
  CHECK(std::count(facing.begin(), facing.end(), 1) == 6);
}

TEST_CASE("facing: a light inside a closed box faces no triangle", "[volumes][facing]") {
  const Mesh box = makeBox({2.0, 2.0, 2.0});
  std::vector<uint8_t> facing;
  computeFacing(box, glm::dvec4(0.3, -0.2, 0.1, 1.0), facing);
  CHECK(std::count(facing.begin(), facing.end(), 1) == 0);
}

TEST_CASE("facing: a light in a face's plane does not face it (strict N·(L − V) > 0)", "[volumes][facing]") {
  const Mesh box = makeBox({2.0, 2.0, 2.0});
  std::vector<uint8_t> facing;
  computeFacing(box, glm::dvec4(1.0, 5.0, 0.0, 1.0), facing);  // in the plane x = 1, above the box
  CHECK(facing == trianglesWithNormal(box, {0, 1, 0}));
  CHECK_FALSE(facesLight({1, 0, 0}, {1, 0, 0}, {1.0, 5.0, 0.0, 1.0}));
  CHECK(facesLight({1, 0, 0}, {1, 0, 0}, {1.5, 5.0, 0.0, 1.0}));
}

TEST_CASE("facing: the light in object space gives the same facing as the mesh moved into the world",
          "[volumes][facing]") {
  std::mt19937_64 rng(4);
  const Mesh sphere = makeSphere(1.0, 12, 8);
  for (int trial = 0; trial < 20; ++trial) {
    const glm::dmat4 world = glm::translate(glm::dmat4(1.0), glm::dvec3(3.0, -1.0, 2.0)) *
                             testing::randomRotation(rng) *
                             glm::scale(glm::dmat4(1.0), glm::dvec3(1.5, 0.5, 2.0));
    const Mesh placed = testing::transformed(sphere, world);
    for (bool directional : {false, true}) {
      glm::dvec4 light = testing::randomLight(rng, directional);
      if (!directional) light += glm::dvec4(3.0, -1.0, 2.0, 0.0);
      std::vector<uint8_t> inWorld, inObject;
      computeFacing(placed, light, inWorld);
      const glm::dvec4 objectLight = lightInObjectSpace(world, light);
      CHECK(objectLight.w == light.w);
      computeFacing(sphere, objectLight, inObject);
      CHECK(inWorld == inObject);
    }
  }
}
