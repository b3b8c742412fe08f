#include "scene/scene_validation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "gl/projection.h"
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
  if (!imagePixels(std::uint64_t(scene.width), std::uint64_t(scene.height)))
    failAt(where.find("image.height"), "image: " + std::to_string(scene.width) + " x " + std::to_string(scene.height) +
                                           " pixels are more than the " + std::to_string(kMaxImagePixels) +
                                           " that can be allocated");
}

// allWithin's bound for "finite": infinity itself is not within it.
constexpr double kLargestFinite = std::numeric_limits<double>::max();

// |v| without under- or overflow of the squares (for messages).
double robustLength(const glm::dvec3& v) {
  const double largest = std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  return largest > 0.0 ? largest * glm::length(v / largest) : 0.0;
}

// A unit vector along v, or not finite when v's squared length under- or overflows.
bool normalisable(const glm::dvec3& v) {
  const glm::dvec3 unit = glm::normalize(v);
  return allWithin(unit, 1.0 + 1e-12) && std::fabs(glm::length(unit) - 1.0) < 1e-12;
}

void validateCamera(const Camera& c, int width, int height, const Provenance& where) {
  const glm::dvec3 view = c.target - c.eye;
  if (!allWithin(view, kLargestFinite))
    failAt(where.find("camera.target"), "camera: target - eye is not finite, there is no view direction");
  if (view == glm::dvec3(0.0))
    failAt(where.find("camera.target"), "camera: eye and target are the same point, there is no view direction");
  // The direction must survive normalisation (its squared length neither underflows) and not be
  // mostly rounding error of the two points' coordinates.
  const double distance = robustLength(view);
  const double scale = std::max(glm::length(c.eye), glm::length(c.target));
  if (!normalisable(view) || !(distance > 1e-9 * scale))
    failAt(where.find("camera.target"), "camera: eye and target are too close together (" + number(distance) +
                                            " apart) to give a view direction");
  if (c.up == glm::dvec3(0.0)) failAt(where.find("camera.up"), "camera.up: the up vector must not be the zero vector");
  if (!normalisable(c.up))
    failAt(where.find("camera.up"), "camera.up: the up vector cannot be normalised to unit length");
  // The view frame is cross(view, up); when the two are (nearly) parallel it does not exist.
  const double sine = glm::length(glm::cross(glm::normalize(view), glm::normalize(c.up)));
  if (!(sine > 1e-9))
    failAt(where.find("camera.up"), "camera.up: the up vector is parallel to the view direction (target - eye)");
  if (!(c.nearPlane < c.farPlane))
    failAt(where.find("camera.far"), "camera: near (" + number(c.nearPlane) + ") must be less than far (" +
                                         number(c.farPlane) + ")");
  // The matrices the renderer builds from these (shadow/scene_view.cpp), checked here so that a
  // value that makes one of them infinite is reported at its key instead of drawing nothing.
  if (!allWithin(lookAt(c.eye, c.target, c.up), kLargestFinite))
    failAt(where.find("camera.eye"), "camera: the view matrix is not finite");
  const double aspect = double(width) / double(height);
  const glm::dmat4 projection = std::isinf(c.farPlane) ? infinitePerspective(c.fovYDegrees, aspect, c.nearPlane)
                                                       : perspective(c.fovYDegrees, aspect, c.nearPlane, c.farPlane);
  if (!allWithin(projection, kLargestFinite))
    failAt(where.find("camera.fov"), "camera: the projection matrix is not finite (fov " + number(c.fovYDegrees) +
                                         ", near " + number(c.nearPlane) + ", far " + number(c.farPlane) + ")");
}

// What the renderer derives from a light: its unit direction, the inverse of its constant
// attenuation at distance 0. Positions and spacings are bounded numbers (kMaxSceneNumber), so the
// soft lights' positions (position + spacing * offset) are finite.
void validateLights(const std::vector<Light>& lights, const Provenance& where) {
  for (size_t i = 0; i < lights.size(); ++i) {
    const Light& l = lights[i];
    const std::string path = "lights." + std::to_string(i);
    if (l.type != LightType::Point && !normalisable(l.direction))
      failAt(where.find(path + ".direction"), path + ".direction: cannot be normalised to unit length");
    if (l.attenuation.x > 0.0 && !std::isfinite(1.0 / l.attenuation.x))
      failAt(where.find(path + ".attenuation"), path + ".attenuation: the constant term " + number(l.attenuation.x) +
                                                    " is so small that its inverse is infinite");
  }
}

// The world bounds of `box` under `m`: the eight corners, transformed (as Scene::instances does).
Aabb transformed(const Aabb& box, const glm::dmat4& m) {
  Aabb out;
  if (box.empty()) return out;
  for (int i = 0; i < 8; ++i) {
    const glm::dvec3 c((i & 1) ? box.max.x : box.min.x, (i & 2) ? box.max.y : box.min.y,
                       (i & 4) ? box.max.z : box.min.z);
    out.add(glm::dvec3(m * glm::dvec4(c, 1.0)));
  }
  return out;
}

// Walks the scene graph as Scene::instances will flatten it, without building an instance:
// world transforms must stay finite, bounded and invertible, and the instances' triangles and
// vertices must fit the budget. Recursive: the nesting is bounded by the document's (kYamlMaxDepth).
class GraphCheck {
 public:
  GraphCheck(const Scene& scene, const ResourceLimits& limits, const Provenance& where)
      : scene_(scene), budget_(limits), where_(where) {}

  void run() {
    for (size_t i = 0; i < scene_.roots.size(); ++i) {
      indices_.assign(1, i);
      visit(scene_.roots[i], glm::dmat4(1.0));
    }
  }

 private:
  std::string path() const {
    std::string p = "nodes";
    for (size_t k = 0; k < indices_.size(); ++k) p += (k ? ".children." : ".") + std::to_string(indices_[k]);
    return p;
  }
  [[noreturn]] void fail(const std::string& message) const {
    const std::string p = path();
    failAt(where_.find(p), p + ": " + message);
  }

  void visit(const Node& node, const glm::dmat4& parent) {
    const glm::dmat4 world = parent * node.local;
    if (!allWithin(world, kMaxWorldMagnitude))
      fail("the world transform has entries beyond +-1e30 (the ancestors' scales and translations multiply up)");
    const glm::dmat3 linear(world);
    const double bound = glm::length(linear[0]) * glm::length(linear[1]) * glm::length(linear[2]);
    if (!(std::abs(glm::determinant(linear)) > 1e-12 * bound))
      fail("the world transform is singular (the ancestors' scales multiply down to nothing)");
    const size_t meshCount = scene_.meshes.size();
    if (node.mesh >= 0 && size_t(node.mesh) < meshCount) {
      const Mesh& mesh = *scene_.meshes[size_t(node.mesh)];
      std::uint64_t triangles = mesh.triangles.size(), vertices = mesh.positions.size();
      if (node.castShadows && node.shadowProxy >= 0 && size_t(node.shadowProxy) < meshCount) {
        triangles += scene_.meshes[size_t(node.shadowProxy)]->triangles.size();
        vertices += scene_.meshes[size_t(node.shadowProxy)]->positions.size();
      }
      if (const std::string exceeded = budget_.add(triangles, vertices); !exceeded.empty()) fail(exceeded);
      const Aabb box = transformed(mesh.bounds, world);
      if (!box.empty() && !(allWithin(box.min, kMaxWorldMagnitude) && allWithin(box.max, kMaxWorldMagnitude)))
        fail("the mesh '" + mesh.name + "' reaches beyond +-1e30 in world space");
    }
    for (size_t i = 0; i < node.children.size(); ++i) {
      indices_.push_back(i);
      visit(node.children[i], world);
      indices_.pop_back();
    }
  }

  const Scene& scene_;
  ResourceBudget budget_;
  const Provenance& where_;
  std::vector<size_t> indices_;
};

}  // namespace

void validateScene(const Scene& scene, const ResourceLimits& limits, const Provenance& where) {
  validateImage(scene, where);
  validateCamera(scene.camera, scene.width, scene.height, where);
  validateLights(scene.lights, where);
  GraphCheck(scene, limits, where).run();
}

}  // namespace shadowref
