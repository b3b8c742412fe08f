// The camera on a shadow-volume face and inside a volume ([Kuhn 2016, §3.4, Fig. 3.3]): z-pass
// counts from the near plane and misses the volumes the near plane starts in; z-fail counts from
// infinity and does not care where the camera is.
//
// Scene (hand-placed so the volume's faces are exact): a 2 x 2 x 2 box centred at (0, 5, 0), a
// point light at (0, 10, 0), a ground slab with its top at y = -2. The light sees the box's top
// face only; the silhouette is the top face's rim at y = 6, and the side through the rim edge
// x = 1 is the plane 4x + y = 10 (it contains (1, 6, z) and runs along (1, -4, 0)).
#include <span>
#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include "extremes/extreme_scene.h"
#include "scene/primitives.h"

using namespace shadowref;
using namespace shadowref::extremes;

namespace {

Scene boxUnderLight(const glm::dvec3& eye, const glm::dvec3& target) {
  Scene scene;
  scene.sourceFile = "<extremes:box-under-light>";
  scene.width = kWidth;
  scene.height = kHeight;
  scene.camera.eye = eye;
  scene.camera.target = target;
  scene.camera.fovYDegrees = 60.0;
  scene.camera.nearPlane = 0.05;
  Light lamp;
  lamp.name = "lamp";
  lamp.position = {0.0, 10.0, 0.0};
  scene.lights.push_back(lamp);
  addObject(scene, "ground", makePlane({30.0, 30.0}, 0.1), glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, -2.0, 0.0)));
  addObject(scene, "box", makeBox(glm::dvec3(2.0)), glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 5.0, 0.0)));
  return scene;
}

size_t differing(std::span<const uint8_t> a, std::span<const uint8_t> b) {
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += a[i] != b[i];
  return n;
}

}  // namespace

TEST_CASE("Camera exactly on a shadow-volume side (4x + y = 10): z-fail equals the oracle's true count, z-pass the "
          "oracle's near-plane count, off edges", "[extremes]") {
  // (2.5, 0, 0) lies on the side's plane and within the side (|z| <= 2.5 there): the face is seen
  // edge-on, a line through the image, and the near plane straddles it.
  const Scene scene = boxUnderLight({2.5, 0.0, 0.0}, {-1.0, -2.0, 0.5});
  const oracle::OracleImage img = castFor(scene);
  const FrameResult zfail = renderStencil(scene, "zfail");
  const FrameResult zpass = renderStencil(scene, "zpass");
  const Agreement f = compare(zfail.stencilPerLight.at(0), img, "zfail");
  const Agreement p = compare(zpass.stencilPerLight.at(0), img, "zpass");
  INFO("z-fail: " << describe(f) << "\nz-pass: " << describe(p));
  CHECK(f.compared > f.pixels / 2);
  CHECK(f.shadowed > 0);
  CHECK(f.countMismatch == 0);
  CHECK(f.maskDisagreeOffEdge == 0);
  CHECK(p.countMismatch == 0);
  // The near plane starts inside the volume for part of the image: there z-pass is one short.
  CHECK(differing(zfail.stencilPerLight[0], zpass.stencilPerLight[0]) > 0);
}

TEST_CASE("Camera inside the shadow volume: z-fail is right, z-pass is one short on every off-edge pixel, so it "
          "lights the shadow and shades the light", "[extremes]") {
  // (0.5, 2, 0.3) is under the box, inside the umbra (|x|, |z| < 2 at y = 2).
  const Scene scene = boxUnderLight({0.5, 2.0, 0.3}, {4.0, -2.0, 1.0});
  const oracle::OracleImage img = castFor(scene);
  const FrameResult zfail = renderStencil(scene, "zfail");
  const FrameResult zpass = renderStencil(scene, "zpass");
  const Agreement f = compare(zfail.stencilPerLight.at(0), img, "zfail");
  const Agreement p = compare(zpass.stencilPerLight.at(0), img, "zpass");
  INFO("z-fail: " << describe(f) << "\nz-pass: " << describe(p));
  CHECK(f.compared > f.pixels / 2);
  CHECK(f.shadowed > 0);
  CHECK(f.shadowed < f.surface);  // both lit and shadowed ground in view
  CHECK(f.countMismatch == 0);
  CHECK(f.maskDisagreeOffEdge == 0);
  // Hand count: the whole near plane lies in exactly one volume, so z-pass = z-fail - 1 (mod 256),
  // and every surface pixel off the edges gets the wrong answer: 0 -> 255 (shaded), 1 -> 0 (lit).
  size_t compared = 0, oneShort = 0, surface = 0, wrongMask = 0;
  for (size_t i = 0; i < img.zfail.size(); ++i) {
    if (img.nearEdge[i]) continue;
    ++compared;
    oneShort += zpass.stencilPerLight[0][i] == uint8_t((img.zfail[i] - 1) & 0xFF);
    if (!img.hitMask[i]) continue;
    ++surface;
    wrongMask += (zpass.stencilPerLight[0][i] == 0) != (img.lit[i] != 0);
  }
  CHECK(oneShort == compared);
  CHECK(wrongMask == surface);
  CHECK(p.countMismatch == 0);  // the oracle's near-plane count predicts exactly that
}
