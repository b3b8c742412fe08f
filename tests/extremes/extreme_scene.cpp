#include "extremes/extreme_scene.h"

#include <span>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/primitives.h"

namespace shadowref::extremes {

size_t addObject(Scene& scene, const std::string& name, Mesh mesh, const glm::dmat4& local, int material) {
  mesh.name = name;
  scene.meshes.push_back(std::make_shared<Mesh>(std::move(mesh)));
  Node node;
  node.name = name;
  node.mesh = static_cast<int>(scene.meshes.size()) - 1;
  node.material = material;
  node.local = local;
  scene.roots.push_back(std::move(node));
  return scene.roots.size() - 1;
}

Scene boxOnGround(int width, int height) {
  Scene scene;
  scene.sourceFile = "<extremes:box-on-ground>";
  scene.width = width;
  scene.height = height;
  scene.camera.eye = {4.0, 3.0, 5.0};
  scene.camera.target = {0.0, 0.5, 0.0};
  scene.camera.fovYDegrees = 50.0;
  scene.camera.nearPlane = 0.1;
  scene.camera.farPlane = kInfinity;
  scene.materials[0].diffuse = glm::dvec3(0.7);
  Material red;
  red.name = "red";
  red.diffuse = {0.8, 0.2, 0.1};
  red.ambient = red.diffuse;  // red even where unlit, so a pixel's colour tells box from ground
  scene.materials.push_back(red);
  Light lamp;
  lamp.name = "lamp";
  lamp.position = {-1.5, 4.0, -1.0};  // behind the box: its shadow falls towards the camera
  scene.lights.push_back(lamp);
  addObject(scene, "ground", makePlane({10.0, 10.0}, 0.1), glm::dmat4(1.0), 0);
  addObject(scene, "box", makeBox(glm::dvec3(1.0)), glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.5, 0.0)), 1);
  scene.shadow.method = "zfail";
  return scene;
}

Scene similar(const Scene& scene, double scale, const glm::dvec3& offset) {
  Scene out = scene;
  const auto map = [&](const glm::dvec3& p) { return scale * p + offset; };
  Node root;
  root.name = "similar";
  root.local = glm::translate(glm::dmat4(1.0), offset) * glm::scale(glm::dmat4(1.0), glm::dvec3(scale));
  root.children = std::move(out.roots);
  out.roots = {std::move(root)};
  out.camera.eye = map(scene.camera.eye);
  out.camera.target = map(scene.camera.target);
  out.camera.nearPlane = scene.camera.nearPlane * scale;
  out.camera.farPlane = scene.camera.farPlane * scale;
  for (Light& light : out.lights) {
    light.position = map(light.position);
    light.range *= scale;
  }
  return out;
}

oracle::OracleImage castFor(const Scene& scene, size_t light) {
  oracle::OracleOptions options;
  options.forceInfiniteProjection = true;  // the volume renderer draws with P_inf ([Kuhn 2016, §3.3])
  return oracle::castOracle(scene, scene.lights.at(light), options);
}

FrameResult renderStencil(const Scene& scene, std::string_view method) {
  FrameOptions options;
  options.method = method;
  options.keepStencil = true;
  return renderFrame(scene, options);
}

Agreement compare(std::span<const uint8_t> stencil, const oracle::OracleImage& img, std::string_view method) {
  const std::vector<int>& counts = method == "zpass" ? img.zpass : img.zfail;
  Agreement a;
  a.pixels = stencil.size();
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const size_t i = img.index(x, y);
      if (img.hitMask[i]) {
        ++a.surface;
        a.shadowed += !img.lit[i];
        const bool disagree = (stencil[i] == 0) != (img.lit[i] != 0);
        a.maskDisagree += disagree;
        a.maskDisagreeOffEdge += disagree && !img.nearEdge[i];
      }
      if (img.nearEdge[i]) continue;
      ++a.compared;
      // An 8-bit wrapping stencil holds the count modulo 256 (INCR_WRAP / DECR_WRAP, [SV slides]).
      if (stencil[i] == uint8_t(counts[i] & 0xFF)) continue;
      if (a.countMismatch++ == 0) {
        std::ostringstream s;
        s << "first mismatch at pixel " << x << "," << y << ": stencil " << int(int8_t(stencil[i])) << ", oracle "
          << counts[i];
        a.firstMismatch = s.str();
      }
    }
  return a;
}

Agreement renderAndCompare(const Scene& scene, std::string_view method, size_t light) {
  const FrameResult frame = renderStencil(scene, method);
  return compare(frame.stencilPerLight.at(light), castFor(scene, light), method);
}

std::string describe(const Agreement& a) {
  std::ostringstream s;
  s << "compared " << a.compared << "/" << a.pixels << " off-edge pixels, " << a.countMismatch
    << " count mismatches; surface " << a.surface << ", shadowed " << a.shadowed << ", mask disagrees on "
    << a.maskDisagree << " (" << a.maskDisagreeOffEdge << " off edges). " << a.firstMismatch;
  return s.str();
}

}  // namespace shadowref::extremes
