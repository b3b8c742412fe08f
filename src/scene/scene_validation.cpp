#include "scene/scene_validation.h"

#include <cstdio>

#include "scene/scene_sections.h"

namespace shadowref {

namespace {

std::string number(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

void validateImage(const Scene& scene, const Provenance& where) {
  if (scene.width == 0) failAt(where.find("image.width"), "image.width: a zero-size image cannot be rendered");
  if (scene.height == 0) failAt(where.find("image.height"), "image.height: a zero-size image cannot be rendered");
  if (scene.width > kMaxImageSide)
    failAt(where.find("image.width"), "image.width: " + std::to_string(scene.width) + " is more than the largest side " +
                                          std::to_string(kMaxImageSide));
  if (scene.height > kMaxImageSide)
    failAt(where.find("image.height"), "image.height: " + std::to_string(scene.height) +
                                           " is more than the largest side " + std::to_string(kMaxImageSide));
  const long long pixels = static_cast<long long>(scene.width) * scene.height;
  if (pixels > kMaxImagePixels)
    failAt(where.find("image.height"), "image: " + std::to_string(scene.width) + " x " + std::to_string(scene.height) +
                                           " pixels are more than the " + std::to_string(kMaxImagePixels) +
                                           " that can be allocated");
}

void validateCamera(const Camera& c, const Provenance& where) {
  const glm::dvec3 view = c.target - c.eye;
  if (view == glm::dvec3(0.0))
    failAt(where.find("camera.target"), "camera: eye and target are the same point, there is no view direction");
  if (c.up == glm::dvec3(0.0)) failAt(where.find("camera.up"), "camera.up: the up vector must not be the zero vector");
  // The view frame is cross(view, up); when the two are (nearly) parallel it does not exist.
  const double sine = glm::length(glm::cross(glm::normalize(view), glm::normalize(c.up)));
  if (!(sine > 1e-9))
    failAt(where.find("camera.up"), "camera.up: the up vector is parallel to the view direction (target - eye)");
  if (!(c.nearPlane < c.farPlane))
    failAt(where.find("camera.far"), "camera: near (" + number(c.nearPlane) + ") must be less than far (" +
                                         number(c.farPlane) + ")");
}

}  // namespace

void validateScene(const Scene& scene, const Provenance& where) {
  validateImage(scene, where);
  validateCamera(scene.camera, where);
}

}  // namespace shadowref
