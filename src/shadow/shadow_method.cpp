#include "shadow/shadow_method.h"

#include <array>

namespace shadowref {

namespace {
constexpr std::array kMethods = {ShadowMethod::None, ShadowMethod::ZPass, ShadowMethod::ZFail,
                                 ShadowMethod::Auto, ShadowMethod::ShadowMap, ShadowMethod::Trapezoidal};
}

const char* name(ShadowMethod method) {
  switch (method) {
    case ShadowMethod::None: return "none";
    case ShadowMethod::ZPass: return "zpass";
    case ShadowMethod::ZFail: return "zfail";
    case ShadowMethod::Auto: return "auto";
    case ShadowMethod::ShadowMap: return "shadowmap";
    case ShadowMethod::Trapezoidal: return "tsm";
  }
  return "?";
}

std::optional<ShadowMethod> parseShadowMethod(std::string_view text) {
  for (ShadowMethod m : kMethods)
    if (text == name(m)) return m;
  return std::nullopt;
}

std::string shadowMethodNames() {
  std::string s;
  for (ShadowMethod m : kMethods) s += std::string(s.empty() ? "" : ", ") + name(m);
  return s;
}

}  // namespace shadowref
