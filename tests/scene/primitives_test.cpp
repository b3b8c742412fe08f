#include <cmath>

#include <catch2/catch.hpp>

#include "scene/adjacency.h"
#include "scene/primitives.h"
#include "mesh_checks.h"

using namespace shadowref;
using shadowref::testing::eulerCharacteristic;
using shadowref::testing::requireClosedOutward;
using shadowref::testing::requireNormalsAgreeWithWinding;

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TEST_CASE("every primitive is a closed outward-wound 2-manifold with V-E+F = 2 (torus 0)", "[mesh]") {
  requireClosedOutward(makeBox({1.0, 2.0, 3.0}));
  requireClosedOutward(makeSphere(1.5, 24, 12));
  requireClosedOutward(makeSphere(1.0, 3, 2));
  requireClosedOutward(makeCylinder(0.5, 2.0, 16));
  requireClosedOutward(makeCylinder(0.5, 2.0, 3));
  requireClosedOutward(makeCone(0.5, 1.0, 16));
  requireClosedOutward(makePlane({10.0, 4.0}, 0.2));
  requireClosedOutward(makePrism(3, 1.0, 2.0));
  requireClosedOutward(makePrism(6, 1.0, 0.5));
  requireClosedOutward(makeTorus(2.0, 0.5, 24, 12), /*genus=*/1);
}

TEST_CASE("primitive render normals point to the outer side of every face", "[mesh]") {
  for (const Mesh& m : {makeBox({1.0, 2.0, 3.0}), makeSphere(1.0, 16, 8), makeCylinder(1.0, 1.0, 12),
                        makeCone(1.0, 2.0, 12), makeTorus(2.0, 0.5, 16, 8), makePlane({2.0, 2.0}, 0.1),
                        makePrism(5, 1.0, 1.0)})
    requireNormalsAgreeWithWinding(m);
}

TEST_CASE("box welds its 24 flat-shaded vertices to 8 corners, 18 edges, 12 triangles", "[mesh]") {
  const Mesh box = makeBox({2.0, 3.0, 4.0});
  CHECK(box.positions.size() == 24);
  CHECK(box.weldedPositions.size() == 8);
  CHECK(box.edges.size() == 18);
  CHECK(box.weldedTriangles.size() == 12);
  CHECK(eulerCharacteristic(box) == 2);
}

TEST_CASE("box volume is exactly the product of its sides and its bounds are centred", "[mesh]") {
  const Mesh box = makeBox({2.0, 3.0, 4.0});
  CHECK(signedVolume(box) == 24.0);
  CHECK(box.bounds.min == glm::dvec3(-1.0, -1.5, -2.0));
  CHECK(box.bounds.max == glm::dvec3(1.0, 1.5, 2.0));
}

TEST_CASE("sphere volume approaches 4/3 pi r^3 from below", "[mesh]") {
  const double r = 2.0;
  const double exact = 4.0 / 3.0 * kPi * r * r * r;
  const double v = signedVolume(makeSphere(r, 64, 32));
  CHECK(v < exact);  // an inscribed polyhedron
  CHECK(v > 0.99 * exact);
}

TEST_CASE("sphere has slices*(stacks-1)+2 welded vertices and 2*slices*(stacks-1) triangles", "[mesh]") {
  const Mesh s = makeSphere(1.0, 10, 6);
  CHECK(s.weldedPositions.size() == 10 * 5 + 2);
  CHECK(s.weldedTriangles.size() == 2 * 10 * 5);
}

TEST_CASE("cylinder and cone volumes match their formulas within the polygon error", "[mesh]") {
  // A regular n-gon of circumradius r has area n/2 r^2 sin(2 pi / n).
  const int n = 32;
  const double polygonArea = n / 2.0 * std::sin(2.0 * kPi / n);
  CHECK(signedVolume(makeCylinder(1.0, 2.0, n)) == Approx(polygonArea * 2.0).epsilon(1e-12));
  CHECK(signedVolume(makeCone(1.0, 3.0, n)) == Approx(polygonArea * 3.0 / 3.0).epsilon(1e-12));
  CHECK(signedVolume(makePrism(4, 1.0, 1.0)) == Approx(2.0).epsilon(1e-12));  // square of diagonal 2
}

TEST_CASE("plane is a slab whose top face lies at y = 0", "[mesh]") {
  const Mesh p = makePlane({6.0, 4.0}, 0.5);
  CHECK(p.bounds.max.y == 0.0);
  CHECK(p.bounds.min.y == -0.5);
  CHECK(p.bounds.max.x == 3.0);
  CHECK(p.bounds.max.z == 2.0);
  CHECK(signedVolume(p) == Approx(12.0));
}

TEST_CASE("torus volume is 2 pi^2 R r^2 within tolerance", "[mesh]") {
  const double exact = 2.0 * kPi * kPi * 2.0 * 0.5 * 0.5;
  CHECK(signedVolume(makeTorus(2.0, 0.5, 96, 48)) == Approx(exact).epsilon(0.01));
}

TEST_CASE("cone apex is one welded vertex although each slice has its own render vertex", "[mesh]") {
  const Mesh c = makeCone(1.0, 2.0, 8);
  // ring 8 + apex + base centre
  CHECK(c.weldedPositions.size() == 10);
}

TEST_CASE("invalid primitive parameters are rejected", "[mesh]") {
  CHECK_THROWS(makeSphere(1.0, 2, 4));
  CHECK_THROWS(makeBox({0.0, 1.0, 1.0}));
  CHECK_THROWS(makeTorus(0.5, 1.0, 8, 8));
  CHECK_THROWS(makePrism(2, 1.0, 1.0));
}
