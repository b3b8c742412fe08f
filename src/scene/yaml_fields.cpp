#include "scene/yaml_fields.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "scene/resource_limits.h"

namespace shadowref {

SourceLocation Provenance::find(std::string path) const {
  for (;;) {
    auto it = at_.find(path);
    if (it != at_.end()) return it->second;
    size_t dot = path.rfind('.');
    if (dot == std::string::npos) return fallback_;
    path.resize(dot);
  }
}

void failAt(const SourceLocation& at, const std::string& message) { throw SceneError(at, message); }

namespace {

const std::string& scalarOf(const YamlValue& v, const std::string& path, const char* expected) {
  if (!v.isScalar()) failAt(v.at, path + ": expected " + expected + ", got " + v.kindName());
  return v.scalar;
}

// YAML spells the special floats .nan, .inf, -.inf (any case); strtod-style parsers know nan, inf.
bool looksNonFinite(std::string_view s) {
  std::string lower;
  for (char c : s) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (std::string_view w : {".nan", ".inf", "+.inf", "-.inf", "nan", "inf", "+inf", "-inf", "infinity",
                             "-infinity", "+infinity"})
    if (lower == w) return true;
  return false;
}

}  // namespace

double readNumber(const YamlValue& v, const std::string& path) {
  const std::string& s = scalarOf(v, path, "a number");
  if (looksNonFinite(s)) failAt(v.at, path + ": '" + s + "' is not allowed, the value must be a finite number");
  std::string_view text = s;
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec == std::errc::result_out_of_range) failAt(v.at, path + ": '" + s + "' is out of the range of a double");
  if (ec != std::errc() || end != text.data() + text.size() || text.empty())
    failAt(v.at, path + ": expected a number, got '" + s + "'");
  if (!std::isfinite(value)) failAt(v.at, path + ": the value must be a finite number");
  // A bound on every number keeps everything computed from them finite (resource_limits.h).
  if (!(std::fabs(value) <= kMaxSceneNumber))
    failAt(v.at, path + ": '" + s + "' is too large; a scene's numbers lie within +-1e15");
  return value;
}

double readNumberInRange(const YamlValue& v, const std::string& path, double min, double max) {
  double x = readNumber(v, path);
  if (x < min || x > max) {
    // The value as written: %g would round 90.0000001 to "90 is outside [0, 90]".
    char buf[160];
    std::snprintf(buf, sizeof buf, " is outside the allowed range [%.17g, %.17g]", min, max);
    failAt(v.at, path + ": " + v.scalar + buf);
  }
  return x;
}

double readPositive(const YamlValue& v, const std::string& path) {
  double x = readNumber(v, path);
  if (!(x > 0.0)) failAt(v.at, path + ": must be greater than 0, got " + v.scalar);
  return x;
}

int readInt(const YamlValue& v, const std::string& path, int min, int max) {
  const std::string& s = scalarOf(v, path, "a whole number");
  std::string_view text = s;
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  long long value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec == std::errc::result_out_of_range || (ec == std::errc() && (value < min || value > max)))
    failAt(v.at, path + ": " + s + " is outside the allowed range [" + std::to_string(min) + ", " +
                     std::to_string(max) + "]");
  if (ec != std::errc() || end != text.data() + text.size() || text.empty())
    failAt(v.at, path + ": expected a whole number, got '" + s + "'");
  return static_cast<int>(value);
}

bool readBool(const YamlValue& v, const std::string& path) {
  const std::string& s = scalarOf(v, path, "true or false");
  for (std::string_view t : {"true", "True", "TRUE", "yes", "Yes", "YES", "on", "On", "ON"})
    if (s == t) return true;
  for (std::string_view f : {"false", "False", "FALSE", "no", "No", "NO", "off", "Off", "OFF"})
    if (s == f) return false;
  failAt(v.at, path + ": expected true or false, got '" + s + "'");
}

std::string readText(const YamlValue& v, const std::string& path) {
  const std::string& s = scalarOf(v, path, "a name");
  if (s.empty()) failAt(v.at, path + ": must not be empty");
  return s;
}

namespace {
template <int N>
glm::vec<N, double> readVector(const YamlValue& v, const std::string& path) {
  const char* expected = N == 3 ? "a list of 3 numbers [x, y, z]" : "a list of 2 numbers [x, y]";
  if (!v.isList()) failAt(v.at, path + ": expected " + expected + ", got " + v.kindName());
  if (v.items.size() != N)
    failAt(v.at, path + ": expected " + expected + ", got " + std::to_string(v.items.size()) + " values");
  glm::vec<N, double> out(0.0);
  for (int i = 0; i < N; ++i) out[i] = readNumber(v.items[i], path + "." + std::to_string(i));
  return out;
}
}  // namespace

glm::dvec3 readVec3(const YamlValue& v, const std::string& path) { return readVector<3>(v, path); }
glm::dvec2 readVec2(const YamlValue& v, const std::string& path) { return readVector<2>(v, path); }

glm::dvec3 readColor(const YamlValue& v, const std::string& path) {
  if (v.isScalar()) return glm::dvec3(readNumber(v, path));
  if (!v.isList() || v.items.size() != 3)
    failAt(v.at, path + ": expected a colour: [r, g, b] or one grey value, got " +
                     (v.isList() ? std::to_string(v.items.size()) + " values" : std::string(v.kindName())));
  return readVec3(v, path);
}

glm::dvec3 readDirection(const YamlValue& v, const std::string& path, const char* what) {
  glm::dvec3 d = readVec3(v, path);
  if (d == glm::dvec3(0.0)) failAt(v.at, path + ": " + what + " must not be the zero vector");
  const double largest = std::max({std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)});
  // Below 2^-400 the squared length (2^-800) underflows; scaling by 2^k is exact and changes no
  // normalised result.
  if (largest < 0x1p-400) {
    const int exponent = std::ilogb(largest);
    d = glm::dvec3(std::ldexp(d.x, -exponent), std::ldexp(d.y, -exponent), std::ldexp(d.z, -exponent));
  }
  const glm::dvec3 unit = glm::normalize(d);
  if (!allWithin(unit, 1.0 + 1e-12) || !(std::fabs(glm::length(unit) - 1.0) < 1e-12))
    failAt(v.at, path + ": " + what + " cannot be normalised to unit length");
  return d;
}

bool allWithin(const glm::dvec3& v, double bound) {
  for (int i = 0; i < 3; ++i)
    if (!(std::fabs(v[i]) <= bound)) return false;  // NaN fails too
  return true;
}

bool allWithin(const glm::dmat4& m, double bound) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!(std::fabs(m[c][r]) <= bound)) return false;
  return true;
}

std::string joinNames(const std::vector<std::string_view>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i) out += ", ";
    out += names[i];
  }
  return out;
}

namespace {
size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}
}  // namespace

std::string_view closestName(std::string_view word, const std::vector<std::string_view>& names) {
  // The edit distance costs |word| * |name|: a suggestion is for a typo in a name of ordinary
  // length, and a name of megabytes or a million long names must not make the error message take
  // hours. The names are compared in their order until the work is spent: deterministic.
  constexpr size_t kLongestSuggested = 256;
  constexpr size_t kMaxWork = size_t(1) << 26;
  if (word.size() > kLongestSuggested) return {};
  std::string_view best;
  size_t bestDistance = std::numeric_limits<size_t>::max();
  size_t work = 0;
  for (std::string_view n : names) {
    if (n.size() > kLongestSuggested) continue;
    work += (word.size() + 1) * (n.size() + 1);
    if (work > kMaxWork) break;
    size_t d = editDistance(word, n);
    if (d < bestDistance) bestDistance = d, best = n;  // first of equals wins: deterministic
  }
  // A suggestion helps only when most of the word survives.
  size_t limit = std::max<size_t>(1, std::min(word.size(), best.size()) / 2);
  return bestDistance <= limit ? best : std::string_view();
}

void checkKeys(const YamlValue& map, const std::string& path, const std::vector<std::string_view>& allowed) {
  std::string what = path.empty() ? "the scene" : path;
  if (!map.isMap()) {
    // An empty section ("camera:") means "all defaults".
    if (map.isNull()) return;
    failAt(map.at, what + ": expected a map of keys (" + joinNames(allowed) + "), got " + map.kindName());
  }
  for (const YamlEntry& e : map.entries) {
    if (std::find(allowed.begin(), allowed.end(), e.key) != allowed.end()) continue;
    std::string message = "unknown key '" + e.key + "' in " + what + " (allowed: " + joinNames(allowed) + ")";
    std::string_view near = closestName(e.key, allowed);
    if (!near.empty()) message += "; did you mean '" + std::string(near) + "'?";
    failAt(e.keyAt, message);
  }
}

}  // namespace shadowref
