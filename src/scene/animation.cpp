#include "scene/animation.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/scene_validation.h"

namespace shadowref {

namespace {

constexpr double kPi = 3.14159265358979323846;

const EnumNames<Interpolation>& interpolationNames() {
  static const EnumNames<Interpolation> names{{"linear", Interpolation::Linear}, {"smooth", Interpolation::Smooth}};
  return names;
}

// The segment [times[i], times[i+1]) that holds t, for times.front() < t < times.back().
size_t segmentOf(const std::vector<double>& times, double t) {
  return size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
}

// The Catmull-Rom tangent (value per second) at key i; 0 at the first and last key.
template <class T>
T tangent(const Track<T>& track, size_t i) {
  const size_t n = track.times.size();
  if (i == 0 || i + 1 >= n) return T(0.0);
  return (track.values[i + 1] - track.values[i - 1]) / (track.times[i + 1] - track.times[i - 1]);
}

template <class T>
T interpolate(const Track<T>& track, double t) {
  const std::vector<double>& times = track.times;
  if (t <= times.front() || times.size() == 1) return track.values.front();
  if (t >= times.back()) return track.values.back();
  const size_t i = segmentOf(times, t);
  const T& p0 = track.values[i];
  const T& p1 = track.values[i + 1];
  const double h = times[i + 1] - times[i];
  const double s = (t - times[i]) / h;
  if (track.interpolation == Interpolation::Step) return p0;
  if (track.interpolation == Interpolation::Linear) return p0 + (p1 - p0) * s;
  const double s2 = s * s, s3 = s2 * s;
  const double h00 = 2.0 * s3 - 3.0 * s2 + 1.0, h10 = s3 - 2.0 * s2 + s;
  const double h01 = 3.0 * s2 - 2.0 * s3, h11 = s3 - s2;
  return p0 * h00 + tangent(track, i) * (h * h10) + p1 * h01 + tangent(track, i + 1) * (h * h11);
}

std::string formatTime(double t) {
  std::ostringstream out;
  out.precision(6);
  out << t;
  return out.str();
}

// ---- reading -------------------------------------------------------------------------------

template <class T>
using ValueReader = T (*)(const YamlValue& v, const std::string& path);

// {interpolation: linear|smooth, keys: {TIME: VALUE, ...}}, times strictly increasing as written.
template <class T>
Track<T> readTrack(const YamlValue& v, const std::string& path, Interpolation defaultInterpolation,
                   ValueReader<T> readValue, bool stepOnly = false) {
  if (!v.isMap())
    failAt(v.at, path + ": expected a track {keys: {TIME: VALUE, ...}} (and optionally interpolation), got " +
                     std::string(v.kindName()));
  checkKeys(v, path, stepOnly ? std::vector<std::string_view>{"keys"}
                              : std::vector<std::string_view>{"interpolation", "keys"});
  Track<T> track;
  track.at = v.at;
  track.interpolation = stepOnly ? Interpolation::Step : defaultInterpolation;
  if (const YamlValue* i = v.find("interpolation"))
    track.interpolation = readEnum(*i, path + ".interpolation", interpolationNames());
  const YamlValue* keys = v.find("keys");
  if (!keys) failAt(v.at, path + ": a track needs keys: {TIME: VALUE, ...}");
  if (!keys->isMap() || keys->entries.empty())
    failAt(keys->at, path + ".keys: expected a map of at least one TIME: VALUE (time in seconds), got " +
                         std::string(keys->kindName()));
  if (keys->entries.size() > kMaxAnimationKeys)
    failAt(keys->at, path + ".keys: more than " + std::to_string(kMaxAnimationKeys) + " keys in one track");
  for (const YamlEntry& e : keys->entries) {
    YamlValue time;
    time.kind = YamlValue::Kind::Scalar;
    time.scalar = e.key;
    time.at = e.keyAt;
    const std::string keyPath = path + ".keys." + e.key;
    const double seconds = readNumber(time, keyPath);
    if (!track.times.empty() && !(seconds > track.times.back()))
      failAt(e.keyAt, keyPath + ": key times must increase in the order written (" + e.key + " follows " +
                          formatTime(track.times.back()) + ")");
    track.times.push_back(seconds);
    track.values.push_back(readValue(e.value, keyPath));
  }
  return track;
}

double readFov(const YamlValue& v, const std::string& path) {
  const double fov = readNumber(v, path);
  if (!(fov > 0.0 && fov < 180.0))
    failAt(v.at, path + ": the vertical field of view must lie strictly between 0 and 180 degrees, got " + v.scalar);
  return fov;
}

glm::dvec3 readAnyDirection(const YamlValue& v, const std::string& path) { return readDirection(v, path); }

glm::dvec3 readNonZeroScale(const YamlValue& v, const std::string& path) {
  const glm::dvec3 s = v.isScalar() ? glm::dvec3(readNumber(v, path)) : readVec3(v, path);
  if (s.x == 0.0 || s.y == 0.0 || s.z == 0.0)
    failAt(v.at, path + ": a scale of 0 flattens the node: the transform is singular");
  return s;
}

void readCamera(const YamlValue& v, Interpolation interp, CameraTracks& camera) {
  checkKeys(v, "animation.camera", {"eye", "target", "fov"});
  if (const YamlValue* x = v.find("eye")) camera.eye = readTrack<glm::dvec3>(*x, "animation.camera.eye", interp, readVec3);
  if (const YamlValue* x = v.find("target"))
    camera.target = readTrack<glm::dvec3>(*x, "animation.camera.target", interp, readVec3);
  if (const YamlValue* x = v.find("fov")) camera.fov = readTrack<double>(*x, "animation.camera.fov", interp, readFov);
}

void readLights(const YamlValue& v, Interpolation interp, const Scene& scene, const std::set<std::string>& removed,
                std::vector<LightTracks>& out) {
  if (!v.isMap()) failAt(v.at, "animation.lights: expected a map of light name: tracks, got " + std::string(v.kindName()));
  for (const YamlEntry& e : v.entries) {
    if (removed.count(e.key)) continue;
    const std::string path = "animation.lights." + e.key;
    LightTracks tracks;
    bool found = false;
    std::vector<std::string_view> names;
    for (size_t i = 0; i < scene.lights.size(); ++i) {
      names.push_back(scene.lights[i].name);
      if (scene.lights[i].name == e.key) tracks.light = i, found = true;  // the last of equal names, as -D
    }
    if (!found) {
      std::string message = path + ": the scene has no light named '" + e.key + "'";
      const std::string_view near = closestName(e.key, names);
      if (!near.empty()) message += "; did you mean '" + std::string(near) + "'?";
      failAt(e.keyAt, message);
    }
    const Light& light = scene.lights[tracks.light];
    if (!e.value.isMap()) failAt(e.value.at, path + ": expected a map of tracks (position, direction, color, on)");
    checkKeys(e.value, path, {"position", "direction", "color", "on"});
    for (const YamlEntry& k : e.value.entries) {
      const bool applies = k.key == "position"    ? light.type != LightType::Directional
                           : k.key == "direction" ? light.type != LightType::Point
                                                  : true;
      if (!applies)
        failAt(k.keyAt, path + "." + k.key + ": a " +
                            std::string(light.type == LightType::Directional ? "directional light has no position"
                                                                             : "point light has no direction"));
    }
    if (const YamlValue* x = e.value.find("position"))
      tracks.position = readTrack<glm::dvec3>(*x, path + ".position", interp, readVec3);
    if (const YamlValue* x = e.value.find("direction"))
      tracks.direction = readTrack<glm::dvec3>(*x, path + ".direction", interp, readAnyDirection);
    if (const YamlValue* x = e.value.find("color"))
      tracks.color = readTrack<glm::dvec3>(*x, path + ".color", interp, readColor);
    if (const YamlValue* x = e.value.find("on")) tracks.on = readTrack<bool>(*x, path + ".on", interp, readBool, true);
    out.push_back(std::move(tracks));
  }
}

// Every node whose path of names ("room/table") is `path`, as index paths.
void findNodes(const std::vector<Node>& nodes, const std::string& prefix, std::vector<size_t>& indices,
               const std::string& path, std::vector<std::vector<size_t>>& found, std::vector<std::string>& all) {
  for (size_t i = 0; i < nodes.size(); ++i) {
    const std::string here = prefix.empty() ? nodes[i].name : prefix + "/" + nodes[i].name;
    indices.push_back(i);
    if (all.size() < 100000) all.push_back(here);
    if (here == path) found.push_back(indices);
    // Only a prefix of the wanted path can lead to it.
    if (path.size() > here.size() && path.compare(0, here.size() + 1, here + "/") == 0)
      findNodes(nodes[i].children, here, indices, path, found, all);
    indices.pop_back();
  }
}

void readNodes(const YamlValue& v, Interpolation interp, const Scene& scene, const std::set<std::string>& removed,
               std::vector<NodeTracks>& out) {
  if (!v.isMap())
    failAt(v.at, "animation.nodes: expected a map of node path (\"room/table\"): tracks, got " + std::string(v.kindName()));
  for (const YamlEntry& e : v.entries) {
    // A node -D removed takes its descendants with it.
    if (std::any_of(removed.begin(), removed.end(), [&](const std::string& r) {
          return e.key == r || e.key.compare(0, r.size() + 1, r + "/") == 0;
        }))
      continue;
    const std::string path = "animation.nodes." + e.key;
    std::vector<std::vector<size_t>> found;
    std::vector<std::string> all;
    std::vector<size_t> indices;
    findNodes(scene.roots, "", indices, e.key, found, all);
    if (found.empty()) {
      std::vector<std::string_view> names(all.begin(), all.end());
      std::string message = path + ": the scene has no node with the path '" + e.key +
                            "' (node names from the root, joined by '/')";
      const std::string_view near = closestName(e.key, names);
      if (!near.empty()) message += "; did you mean '" + std::string(near) + "'?";
      failAt(e.keyAt, message);
    }
    if (found.size() > 1)
      failAt(e.keyAt, path + ": " + std::to_string(found.size()) + " nodes have the path '" + e.key +
                          "'; give the nodes distinct names to animate one");
    NodeTracks tracks;
    tracks.indexPath = found.front();
    tracks.path = e.key;
    if (!e.value.isMap()) failAt(e.value.at, path + ": expected a map of tracks (translate, rotate, scale)");
    checkKeys(e.value, path, {"translate", "rotate", "scale"});
    if (const YamlValue* x = e.value.find("translate"))
      tracks.translate = readTrack<glm::dvec3>(*x, path + ".translate", interp, readVec3);
    if (const YamlValue* x = e.value.find("rotate"))
      tracks.rotate = readTrack<glm::dvec3>(*x, path + ".rotate", interp, readVec3);
    if (const YamlValue* x = e.value.find("scale"))
      tracks.scale = readTrack<glm::dvec3>(*x, path + ".scale", interp, readNonZeroScale);
    out.push_back(std::move(tracks));
  }
}

template <class T>
void widen(double& latest, const std::optional<Track<T>>& track) {
  if (track) latest = std::max(latest, track->times.back());
}

// T(translate) · Rz · Ry · Rx · S(scale), the order the node section composes in.
glm::dmat4 nodeMotion(const NodeTracks& tracks, double t) {
  const glm::dmat4 id(1.0);
  glm::dmat4 m(1.0);
  if (tracks.translate) m = glm::translate(m, evaluate(*tracks.translate, t));
  if (tracks.rotate) {
    const glm::dvec3 e = evaluate(*tracks.rotate, t) * (kPi / 180.0);
    m = m * glm::rotate(id, e.z, glm::dvec3(0, 0, 1)) * glm::rotate(id, e.y, glm::dvec3(0, 1, 0)) *
        glm::rotate(id, e.x, glm::dvec3(1, 0, 0));
  }
  if (tracks.scale) m = glm::scale(m, evaluate(*tracks.scale, t));
  return m;
}

}  // namespace

double evaluate(const Track<double>& track, double t) { return interpolate(track, t); }
glm::dvec3 evaluate(const Track<glm::dvec3>& track, double t) { return interpolate(track, t); }
bool evaluate(const Track<bool>& track, double t) {
  if (t <= track.times.front() || track.times.size() == 1) return track.values.front();
  if (t >= track.times.back()) return track.values.back();
  return track.values[segmentOf(track.times, t)];
}

double Animation::lastKeyTime() const {
  double latest = 0.0;
  widen(latest, camera.eye);
  widen(latest, camera.target);
  widen(latest, camera.fov);
  for (const LightTracks& l : lights) {
    widen(latest, l.position);
    widen(latest, l.direction);
    widen(latest, l.color);
    widen(latest, l.on);
  }
  for (const NodeTracks& n : nodes) {
    widen(latest, n.translate);
    widen(latest, n.rotate);
    widen(latest, n.scale);
  }
  return latest;
}

Animation readAnimation(const YamlValue& section, const Scene& scene, const ResourceLimits& limits,
                        const RemovedNames& removed) {
  if (!section.isMap())
    failAt(section.at, "animation: expected a map (fps, interpolation, camera, lights, nodes), got " +
                           std::string(section.kindName()));
  checkKeys(section, "animation", {"fps", "interpolation", "camera", "lights", "nodes"});
  Animation a;
  a.limits = limits;
  a.at = section.at;
  if (const YamlValue* v = section.find("fps")) {
    a.fps = readNumber(*v, "animation.fps");
    if (!(a.fps > 0.0 && a.fps <= kMaxAnimationFps))
      failAt(v->at, "animation.fps: frames per second must be greater than 0 and at most " +
                        formatTime(kMaxAnimationFps) + ", got " + v->scalar);
  }
  Interpolation interp = Interpolation::Linear;
  if (const YamlValue* v = section.find("interpolation")) interp = readEnum(*v, "animation.interpolation", interpolationNames());
  if (const YamlValue* v = section.find("camera")) {
    if (!v->isMap()) failAt(v->at, "animation.camera: expected a map of tracks (eye, target, fov)");
    readCamera(*v, interp, a.camera);
  }
  if (const YamlValue* v = section.find("lights")) readLights(*v, interp, scene, removed.lights, a.lights);
  if (const YamlValue* v = section.find("nodes")) readNodes(*v, interp, scene, removed.nodes, a.nodes);
  return a;
}

Scene sceneAt(const Scene& scene, double t) {
  if (!scene.animation) return scene;
  const Animation& a = *scene.animation;
  Scene out = scene;
  out.animation.reset();
  // A failed check names the track that set the value (the section when no track did).
  Provenance where{a.at};
  // A camera check of a value no track sets (target == eye with only the eye moving) points at
  // the camera's first track.
  for (const SourceLocation* at : {a.camera.fov ? &a.camera.fov->at : nullptr, a.camera.target ? &a.camera.target->at : nullptr,
                                   a.camera.eye ? &a.camera.eye->at : nullptr})
    if (at) where.record("camera", *at);
  if (a.camera.eye) out.camera.eye = evaluate(*a.camera.eye, t), where.record("camera.eye", a.camera.eye->at);
  if (a.camera.target)
    out.camera.target = evaluate(*a.camera.target, t), where.record("camera.target", a.camera.target->at);
  if (a.camera.fov) {
    out.camera.fovYDegrees = evaluate(*a.camera.fov, t);
    where.record("camera.fov", a.camera.fov->at);
    // A smooth track can overshoot its keys.
    if (!(out.camera.fovYDegrees > 0.0 && out.camera.fovYDegrees < 180.0))
      failAt(a.camera.fov->at, "animation.camera.fov: the field of view at t = " + formatTime(t) + " s is " +
                                   formatTime(out.camera.fovYDegrees) + " degrees, outside 0 to 180");
  }
  std::vector<bool> keep(out.lights.size(), true);
  for (const LightTracks& l : a.lights) {
    Light& light = out.lights[l.light];
    if (l.position) light.position = evaluate(*l.position, t);
    if (l.direction) light.direction = evaluate(*l.direction, t);
    if (l.color) light.color = evaluate(*l.color, t);
    if (l.on) keep[l.light] = evaluate(*l.on, t);
  }
  for (const NodeTracks& n : a.nodes) {
    Node* node = &out.roots[n.indexPath.front()];
    for (size_t k = 1; k < n.indexPath.size(); ++k) node = &node->children[n.indexPath[k]];
    node->local = node->local * nodeMotion(n, t);
  }
  // The lights that stay, and where their tracks are for the checks (indices after removal).
  std::vector<Light> lights;
  for (size_t i = 0; i < out.lights.size(); ++i) {
    if (!keep[i]) continue;
    for (const LightTracks& l : a.lights) {
      if (l.light != i) continue;
      const std::string path = "lights." + std::to_string(lights.size());
      if (l.position) where.record(path + ".position", l.position->at);
      if (l.direction) where.record(path + ".direction", l.direction->at);
      if (l.color) where.record(path + ".color", l.color->at);
    }
    lights.push_back(std::move(out.lights[i]));
  }
  out.lights = std::move(lights);
  try {
    validateScene(out, a.limits, where);
  } catch (const SceneError& e) {
    throw SceneError(e.where(), e.message() + " (the animation at t = " + formatTime(t) + " s)");
  }
  return out;
}

}  // namespace shadowref
