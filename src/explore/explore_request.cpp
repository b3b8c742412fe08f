#include "explore/explore_request.h"

#include <algorithm>
#include <charconv>

namespace shadowref::explore {

namespace {

// A whole number in [lo, hi], written as plain decimal digits with an optional '-'.
bool parseInt(const std::string& text, int lo, int hi, int& out) {
  int v = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (ec != std::errc() || ptr != end || text.empty()) return false;
  if (v < lo || v > hi) return false;
  out = v;
  return true;
}

}  // namespace

std::optional<std::string> parseRequest(const QueryParams& params, const std::vector<std::string>& allowed,
                                        ExploreRequest& request) {
  const auto isAllowed = [&](const std::string& name) {
    return std::find(allowed.begin(), allowed.end(), name) != allowed.end();
  };
  for (const auto& [name, value] : params) {
    if (!isAllowed(name)) return "unknown parameter '" + name.substr(0, 64) + "'";
    if (name != "D" && params.count(name) > 1) return "parameter '" + name + "' given more than once";
  }
  const auto range = params.equal_range("D");
  for (auto it = range.first; it != range.second; ++it) {
    if (request.overrides.size() == kMaxOverrides)
      return "more than " + std::to_string(kMaxOverrides) + " D parameters";
    if (it->second.size() > kMaxOverrideLength)
      return "a D parameter longer than " + std::to_string(kMaxOverrideLength) + " characters";
    if (it->second.find('\0') != std::string::npos || it->second.find('\n') != std::string::npos)
      return "a D parameter with a NUL or newline character";
    request.overrides.push_back(it->second);
  }
  if (const auto it = params.find("view"); it != params.end() && !parseView(it->second, request.view.view))
    return "view: '" + it->second.substr(0, 64) +
           "' is not one of frame, stencil, volumes, overlay, depth, shadowmap, visibility, pass";
  if (const auto it = params.find("index"); it != params.end() && !parseInt(it->second, 0, 100000, request.view.index))
    return "index: expected a whole number from 0 to 100000, got '" + it->second.substr(0, 64) + "'";
  if (const auto it = params.find("signed"); it != params.end()) {
    if (it->second != "0" && it->second != "1") return "signed: expected 0 or 1, got '" + it->second.substr(0, 64) + "'";
    request.view.signedCounts = it->second == "1";
  }
  for (const char* axis : {"x", "y"}) {
    const auto it = params.find(axis);
    if (it == params.end()) continue;
    int& v = axis[0] == 'x' ? request.x : request.y;
    if (!parseInt(it->second, 0, 1 << 20, v))
      return std::string(axis) + ": expected a whole number from 0, got '" + it->second.substr(0, 64) + "'";
  }
  if (const auto it = params.find("encoding"); it != params.end()) {
    if (it->second != "raw" && it->second != "png") return "encoding: expected raw or png, got '" + it->second.substr(0, 64) + "'";
    request.png = it->second == "png";
  }
  if (const auto it = params.find("seq"); it != params.end()) {
    int seq = 0;
    if (!parseInt(it->second, 0, 2147483647, seq)) return "seq: expected a whole number from 0";
  }
  return std::nullopt;
}

}  // namespace shadowref::explore
