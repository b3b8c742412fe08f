#include "views/value_label.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace shadowref::views {

std::string rangeLabel(double value, double lo, double hi) {
  if (!std::isfinite(value)) return "-";
  const double span = std::abs(hi - lo);
  const int decimals = span > 0.0 && std::isfinite(span) ? std::clamp(2 - int(std::floor(std::log10(span))), 0, 8) : 3;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);  // %f: no exponent, the same text everywhere
  std::string s = buf;
  return s == "-0" || s.find_first_not_of("-0.") == std::string::npos ? s.substr(s[0] == '-' ? 1 : 0) : s;
}

}  // namespace shadowref::views
