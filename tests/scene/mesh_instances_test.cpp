#include <catch2/catch.hpp>

#include "scene/primitives.h"
#include "scene/scene.h"

using namespace shadowref;

namespace {
glm::dmat4 translate(double x, double y, double z) {
  glm::dmat4 m(1.0);
  m[3] = glm::dvec4(x, y, z, 1.0);
  return m;
}
}  // namespace

TEST_CASE("instances flatten the node tree depth-first with world = parent * local", "[mesh]") {
  Scene scene;
  scene.meshes.push_back(std::make_shared<Mesh>(makeBox({2.0, 2.0, 2.0})));
  scene.meshes.push_back(std::make_shared<Mesh>(makeBox({1.0, 1.0, 1.0})));
  Node root;
  root.name = "a";
  root.local = translate(10, 0, 0);
  Node child;
  child.name = "b";
  child.mesh = 0;
  child.local = glm::dmat4(2.0);  // scale x, y, z by 2
  child.local[3][3] = 1.0;
  Node grandchild;
  grandchild.name = "c";
  grandchild.mesh = 1;
  grandchild.local = translate(0, 1, 0);
  grandchild.castShadows = false;
  child.children.push_back(grandchild);
  Node sibling;
  sibling.name = "d";
  sibling.mesh = 0;
  sibling.shadowProxy = 1;
  root.children = {child, sibling};
  scene.roots.push_back(root);

  const std::vector<Instance> inst = scene.instances();
  REQUIRE(inst.size() == 3);
  CHECK(inst[0].path == "a/b");
  CHECK(inst[1].path == "a/b/c");
  CHECK(inst[2].path == "a/d");
  // a/b: box of side 2 scaled by 2 around (10, 0, 0).
  CHECK(inst[0].worldBounds.min == glm::dvec3(8.0, -2.0, -2.0));
  CHECK(inst[0].worldBounds.max == glm::dvec3(12.0, 2.0, 2.0));
  // a/b/c: the translation is scaled by its parent: centre at (10, 2, 0), side 2.
  CHECK(inst[1].worldBounds.min == glm::dvec3(9.0, 1.0, -1.0));
  CHECK(inst[1].worldBounds.max == glm::dvec3(11.0, 3.0, 1.0));
  CHECK(inst[0].shadowMesh == inst[0].mesh);
  CHECK(inst[1].shadowMesh == nullptr);
  CHECK(inst[2].shadowMesh == scene.meshes[1].get());
  CHECK(inst[2].mesh == scene.meshes[0].get());
}

TEST_CASE("world bounds of a rotated box enclose all eight transformed corners", "[mesh]") {
  Scene scene;
  scene.meshes.push_back(std::make_shared<Mesh>(makeBox({2.0, 2.0, 2.0})));
  Node n;
  n.name = "r";
  n.mesh = 0;
  // 90 degrees about z: (x, y) -> (-y, x)
  n.local = glm::dmat4(glm::dvec4(0, 1, 0, 0), glm::dvec4(-1, 0, 0, 0), glm::dvec4(0, 0, 1, 0), glm::dvec4(0, 0, 0, 1));
  n.local[3] = glm::dvec4(0, 5, 0, 1);
  scene.roots.push_back(n);
  const auto inst = scene.instances();
  REQUIRE(inst.size() == 1);
  CHECK(inst[0].worldBounds.min == glm::dvec3(-1.0, 4.0, -1.0));
  CHECK(inst[0].worldBounds.max == glm::dvec3(1.0, 6.0, 1.0));
}
