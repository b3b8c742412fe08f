// Typed reading of YAML values for the scene loader: numbers, vectors, colours, enums, and maps
// whose keys are checked against a table of fields. Every failure is a SceneError at the value's
// (or the key's) location that names the field by its path ("lights.0.range").
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "scene/yaml_document.h"

namespace shadowref {

// Where each scene field was last set, by its path ("camera.near"), so that checks made after
// the whole scene is assembled (near < far, up not parallel to the view) can point at the line
// that is wrong — in the file or on the command line.
class Provenance {
 public:
  explicit Provenance(SourceLocation fallback) : fallback_(std::move(fallback)) {}
  void record(const std::string& path, const SourceLocation& at) { at_[path] = at; }
  // The location of `path`, else of its nearest recorded parent ("camera"), else the fallback.
  SourceLocation find(std::string path) const;

 private:
  std::map<std::string, SourceLocation> at_;
  SourceLocation fallback_;
};

[[noreturn]] void failAt(const SourceLocation& at, const std::string& message);

// Finite (no NaN, no Inf) and of magnitude at most kMaxSceneNumber (resource_limits.h).
double readNumber(const YamlValue& v, const std::string& path);
double readNumberInRange(const YamlValue& v, const std::string& path, double min, double max);
double readPositive(const YamlValue& v, const std::string& path);  // > 0, finite
int readInt(const YamlValue& v, const std::string& path, int min, int max);
bool readBool(const YamlValue& v, const std::string& path);
std::string readText(const YamlValue& v, const std::string& path);  // a scalar, non-empty
glm::dvec3 readVec3(const YamlValue& v, const std::string& path);   // [x, y, z]
glm::dvec2 readVec2(const YamlValue& v, const std::string& path);   // [x, y]
glm::dvec3 readColor(const YamlValue& v, const std::string& path);  // [r, g, b] or one grey value
// A direction [x, y, z]: not the zero vector (`what` names it in the message: "a direction",
// "the rotation axis"). Components so small that the squared length underflows ([1e-320, 0, 0])
// are scaled by a power of two, exactly, into the normal range, so that every later
// glm::normalize of it is finite and a direction in the usual range keeps its bits.
glm::dvec3 readDirection(const YamlValue& v, const std::string& path, const char* what = "a direction");

// True when every component (every entry) is finite and of magnitude at most `bound`.
bool allWithin(const glm::dvec3& v, double bound);
bool allWithin(const glm::dmat4& m, double bound);

template <class E>
using EnumNames = std::vector<std::pair<std::string_view, E>>;

std::string joinNames(const std::vector<std::string_view>& names);
// The name in `names` closest to `word` by edit distance, or "" when none is close.
std::string_view closestName(std::string_view word, const std::vector<std::string_view>& names);

template <class E>
E readEnum(const YamlValue& v, const std::string& path, const EnumNames<E>& names) {
  std::string text = readText(v, path);
  std::vector<std::string_view> all;
  for (const auto& [name, value] : names) {
    if (name == text) return value;
    all.push_back(name);
  }
  std::string message = path + ": '" + text + "' is not one of " + joinNames(all);
  std::string_view near = closestName(text, all);
  if (!near.empty()) message += "; did you mean '" + std::string(near) + "'?";
  failAt(v.at, message);
}

// One key of a map section and how it is applied to the target object.
template <class T>
struct Field {
  std::string_view key;
  // `path` names the field ("lights.0.range"); `where` lets nested sections record their keys.
  std::function<void(const YamlValue& value, T& target, const std::string& path, Provenance& where)> apply;
};

// Checks that `map` is a map whose keys are all in `fields` (an unknown key is an error that
// lists the allowed keys and suggests the closest) and applies each entry in the order written,
// recording its location under "path.key".
void checkKeys(const YamlValue& map, const std::string& path, const std::vector<std::string_view>& allowed);

template <class T>
void applyFields(const YamlValue& map, const std::string& path, const std::vector<Field<T>>& fields,
                 T& target, Provenance& where) {
  std::vector<std::string_view> allowed;
  for (const Field<T>& f : fields) allowed.push_back(f.key);
  checkKeys(map, path, allowed);
  for (const YamlEntry& e : map.entries) {
    std::string fieldPath = path.empty() ? e.key : path + "." + e.key;
    for (const Field<T>& f : fields)
      if (f.key == e.key) f.apply(e.value, target, fieldPath, where);
    where.record(fieldPath, e.value.at);
  }
}

}  // namespace shadowref
