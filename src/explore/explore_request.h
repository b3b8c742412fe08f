// The explorer's requests: query parameters checked before anything is rendered. A request that
// names an unknown parameter, repeats one that is single, or gives a value out of its range is
// refused with the reason (the server answers 400 with it).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "explore/views_adapter.h"

namespace shadowref::explore {

// The parameters as the HTTP library parsed them: each name with its values in order.
using QueryParams = std::multimap<std::string, std::string>;

inline constexpr size_t kMaxOverrides = 64;        // `D` parameters in one request
inline constexpr size_t kMaxOverrideLength = 512;  // characters of one `D` value

struct ExploreRequest {
  std::vector<std::string> overrides;  // the D values, in order
  ViewRequest view;
  int x = -1, y = -1;                  // a pixel (history), framebuffer coordinates
  bool png = false;                    // encoding=png: a picture without values as PNG
};

// Checks the parameters `allowed` names (any of: D, view, index, signed, x, y, seq, encoding) and fills the
// request; the reason on failure. x and y are checked against the image later, once the scene is
// loaded.
std::optional<std::string> parseRequest(const QueryParams& params, const std::vector<std::string>& allowed,
                                        ExploreRequest& request);

}  // namespace shadowref::explore
