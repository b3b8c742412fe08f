// Animation: keyframed tracks for the camera, the lights and node transforms (the `animation:`
// section of a scene file, docs/scene-format.md "Animation"), and the scene at a time t.
//
// sceneAt is a pure function of (scene, t): it starts from the scene as loaded (the values the
// file wrote, which the tracks replace) and returns a still scene, so one process can render any
// frames in any order and frame t is the same bytes as a scene file that writes those values.
#pragma once

#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/resource_limits.h"
#include "scene/scene.h"
#include "scene/yaml_fields.h"

namespace shadowref {

// How a track moves between two keys.
//   Linear: p(t) = p_i + s (p_{i+1} - p_i), s = (t - t_i) / (t_{i+1} - t_i).
//   Smooth: a cubic Hermite segment through p_i and p_{i+1} whose tangents (per second) are the
//     Catmull-Rom finite differences m_i = (p_{i+1} - p_{i-1}) / (t_{i+1} - t_{i-1}) at inner keys
//     and 0 at the first and last key (the motion starts and stops at rest):
//       p(t) = h00 p_i + h10 h m_i + h01 p_{i+1} + h11 h m_{i+1},  h = t_{i+1} - t_i,
//       h00 = 2s^3 - 3s^2 + 1, h10 = s^3 - 2s^2 + s, h01 = 3s^2 - 2s^3, h11 = s^3 - s^2.
//     Between two keys alone this is smoothstep: p_i + (3s^2 - 2s^3)(p_{i+1} - p_i). The curve is
//     C1 (position and velocity continuous) and passes through every key.
//   Step: the value of the last key at or before t (the only choice for on/off).
// Before the first key a track holds the first key's value, after the last the last's.
enum class Interpolation : uint8_t { Linear, Smooth, Step };

template <class T>
struct Track {
  Interpolation interpolation = Interpolation::Linear;
  std::vector<double> times;  // strictly increasing, at least one
  std::vector<T> values;      // one per time
  SourceLocation at;          // where the track is written, for messages
};

double evaluate(const Track<double>& track, double t);
glm::dvec3 evaluate(const Track<glm::dvec3>& track, double t);
bool evaluate(const Track<bool>& track, double t);

struct CameraTracks {
  std::optional<Track<glm::dvec3>> eye, target;
  std::optional<Track<double>> fov;  // degrees, vertical
};

struct LightTracks {
  size_t light = 0;  // index into Scene::lights as loaded
  std::optional<Track<glm::dvec3>> position, direction, color;
  std::optional<Track<bool>> on;  // off: the light is left out of the frame, as -D lights.NAME=off does
};

// The node's local transform at t is local · T(translate) · Rz · Ry · Rx (rotate, degrees) · S(scale):
// the motion happens in the node's own frame, about its origin, inside the placement the file wrote.
struct NodeTracks {
  std::vector<size_t> indexPath;  // root index, then child indices
  std::string path;               // "room/table", as instances are named
  std::optional<Track<glm::dvec3>> translate, rotate, scale;
};

struct Animation {
  double fps = 24.0;  // frame n shows t = n / fps seconds
  CameraTracks camera;
  std::vector<LightTracks> lights;
  std::vector<NodeTracks> nodes;
  ResourceLimits limits;  // the scene's budget: each frame is validated as a loaded scene is
  SourceLocation at;      // the animation section
  double lastKeyTime() const;  // the latest key of any track (0 with none)
};

// Reads the `animation:` section against the loaded scene (lights by name, nodes by path).
// Tracks of the lights and node paths in `removed` (taken out by -D NAME=off) are skipped: the
// command line turned them off. Throws SceneError at the offending key.
struct RemovedNames {
  std::set<std::string> lights, nodes;
};
Animation readAnimation(const YamlValue& section, const Scene& scene, const ResourceLimits& limits,
                        const RemovedNames& removed = {});

// The scene at time t (seconds): every track's value applied, lights that are off removed, the
// result validated as a loaded scene is (a camera whose eye meets its target, a zero direction,
// a singular node transform are SceneErrors at the track, naming t). The result has no
// animation. A scene without animation is returned unchanged.
Scene sceneAt(const Scene& scene, double t);

}  // namespace shadowref
