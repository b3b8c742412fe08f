// The scene model: what a scene file describes, after loading and validation.
// Plain data; the loader (scene_loader.h) and the generators (generators.h) produce it, the
// renderer and the shadow algorithms read it.
#pragma once

#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/framebuffer.h"
#include "scene/mesh.h"
#include "scene/scene_error.h"

namespace shadowref {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Camera {
  glm::dvec3 eye{0.0, 0.0, 5.0};
  glm::dvec3 target{0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fovYDegrees = 60.0;
  double nearPlane = 0.1;
  double farPlane = kInfinity;  // infinity: the infinite projection P_inf ([Kuhn 2016, §3.3])
};

enum class ShadingModel : uint8_t { Gouraud, PerPixel };

// Phong illumination ([Kuhn 2016, §2.3]).
struct Material {
  std::string name = "default";
  glm::dvec3 ambient{0.2};
  glm::dvec3 diffuse{0.8};
  glm::dvec3 specular{0.0};
  double shininess = 32.0;
  ShadingModel shading = ShadingModel::PerPixel;
  bool blinn = false;  // Blinn-Phong half vector instead of the reflection vector
};

enum class LightType : uint8_t { Point, Directional, Spot };

// How a light is spread into several for soft shadows ([Kuhn 2016, §3.6], [Hempe 2004, §4.2]).
enum class SoftShape : uint8_t {
  None,
  SquareX, SquareY, SquareZ,  // the light plus 8 lights on a square in that plane ([Kuhn 2016, §3.6])
  Sphere14,                   // the light plus 14 on a sphere: 6 axis + 8 diagonal ([Kuhn 2016, §3.6])
  AreaEdge16,                 // 16 lights evenly on the edge of a square area light ([Hempe 2004, §4.2])
};

struct Light {
  std::string name;
  LightType type = LightType::Point;
  glm::dvec3 position{0.0, 5.0, 0.0};    // point and spot
  glm::dvec3 direction{0.0, -1.0, 0.0};  // spot: axis; directional: the direction light travels
  glm::dvec3 color{1.0};                 // diffuse and specular intensity
  double range = kInfinity;              // [Kuhn 2016, §4.3.1]
  double spotCutoffDegrees = 45.0;
  double spotExponent = 0.0;
  glm::dvec3 attenuation{1.0, 0.0, 0.0}; // constant, linear, quadratic
  SoftShape soft = SoftShape::None;
  double softSpacing = 0.1;              // distance of the extra lights, or the area's side

  // The light as a homogeneous point: (position, 1), or for a directional light the direction
  // towards the light with w = 0 (L_w of [Kuhn 2016, §4.3.3]).
  glm::dvec4 homogeneous() const {
    if (type == LightType::Directional) return glm::dvec4(-glm::normalize(direction), 0.0);
    return glm::dvec4(position, 1.0);
  }
};

enum class SilhouetteAlgorithm : uint8_t { Kuhn, YenKwoon, Kilgard, Lengyel };

// What a directional light's standard map is fitted to: the casters that can shadow what the
// camera sees (src/shadow/caster_fit.h), or the whole scene's box ([Hempe 2004, §5.1.2]).
enum class MapFit : uint8_t { Casters, Scene };
// What the depth a shadow-map tap compares follows ([Isidoro 2006], ShadowLookup): Off, the
// fragment's own depth at every tap; Kernel, with PCF the receiver's plane at every tap's texel
// centre (nearest sampling compares the fragment's depth); Texel, that for nearest sampling too.
enum class ReceiverPlaneBias : uint8_t { Off, Kernel, Texel };

// Parameters of the shadow algorithms; each technique reads the fields its registry entry lists.
struct ShadowSettings {
  // The shadow technique, by the name it is registered under (src/shadow/technique_registry.h).
  // The scene does not know the list: the name is looked up where the frame is rendered (and by
  // the command line right after loading), and an unknown one is reported at `methodAt`, where
  // the file or the -D override wrote it.
  std::string method = "none";
  SourceLocation methodAt;
  // Shadow volumes ([Kuhn 2016], [SV slides], [DSS article])
  SilhouetteAlgorithm silhouette = SilhouetteAlgorithm::Kuhn;
  bool twoSidedStencil = true;   // one pass with front/back stencil state, or two culled passes
  bool wrapOps = true;           // INCR_WRAP/DECR_WRAP; false: saturating INCR/DECR
  bool darkenComposite = false;  // [SV slides]: lit scene first, then ambient again where stencil != 0
  // Shadow maps ([Hempe 2004])
  int mapSize = 1024;
  double offsetFactor = 1.1, offsetUnits = 4.0;  // polygon offset in the map pass
  double constantBias = 0.0;
  bool backFacesOnly = false;
  int pcf = 1;                    // k x k percentage-closer filtering; 1 = nearest
  ReceiverPlaneBias receiverPlaneBias = ReceiverPlaneBias::Kernel;
  MapFit fit = MapFit::Casters;   // directional light, standard map
  double compareFail = 0.4;       // [Hempe 2004, §5.1.2]
  double focusRegion = 0.4;       // TSM 80 % rule ([Hempe 2004, §4.1])
};

struct Node {
  std::string name;
  glm::dmat4 local{1.0};
  int mesh = -1;          // index into Scene::meshes, -1 for a pure transform node
  int material = 0;       // index into Scene::materials
  bool castShadows = true;
  int shadowProxy = -1;   // low-poly mesh used for the volumes instead of `mesh` ([DSS article])
  std::vector<Node> children;
};

// A mesh placed in the world: the flattened scene graph.
struct Instance {
  std::string path;       // node names from the root, "room/table/leg0"
  const Mesh* mesh = nullptr;
  const Mesh* shadowMesh = nullptr;  // mesh or its proxy; nullptr when it casts no shadow
  glm::dmat4 world{1.0};
  int material = 0;
  Aabb worldBounds;
  Aabb shadowBounds;      // world bounds of shadowMesh (the proxy's, when there is one)
  bool mirrored = false;  // det(world) < 0: windings flip in window space
};

struct Animation;  // scene/animation.h

struct Scene {
  std::string sourceFile;  // for messages; "<builtin:room>" for generators
  int width = 800, height = 640;
  DepthFormat depthFormat = DepthFormat::Float32;
  Camera camera;
  glm::dvec3 ambient{0.2};  // global ambient light
  glm::dvec3 background{0.0};
  std::vector<Light> lights;
  std::vector<Material> materials{Material{}};
  std::vector<std::shared_ptr<Mesh>> meshes;
  std::vector<Node> roots;
  ShadowSettings shadow;
  // The file's `animation:` section, or null for a still scene; sceneAt (scene/animation.h)
  // evaluates it. Shared: copies of a scene share the immutable tracks.
  std::shared_ptr<const Animation> animation;

  // The mesh nodes flattened, depth-first, children after their parent.
  std::vector<Instance> instances() const;
};

// The world bounds of every instance together (instances without bounds add nothing).
Aabb worldBounds(const std::vector<Instance>& instances);

}  // namespace shadowref
