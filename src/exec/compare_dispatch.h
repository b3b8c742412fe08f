// A comparison function (GL's NEVER … ALWAYS) fixed at compile time, for the loops that test
// many values with one function: the depth and stencil tests of the span loops, the shadow-map
// compare. withCompare turns the run-time function into a compile-time one once per loop.
#pragma once

#include <type_traits>

#include "gl/render_state.h"

namespace shadowref {

// A depth or stencil comparison with its function fixed at compile time, so the span loops carry
// no switch: a bool for two codes, a lane mask (all ones where it passes) for two vectors of codes.
template <CompareFunc F, class T>
inline auto passes(T incoming, T stored) {
  const auto result = [&] {
    if constexpr (F == CompareFunc::Never) return incoming != incoming;
    else if constexpr (F == CompareFunc::Less) return incoming < stored;
    else if constexpr (F == CompareFunc::Equal) return incoming == stored;
    else if constexpr (F == CompareFunc::LEqual) return incoming <= stored;
    else if constexpr (F == CompareFunc::Greater) return incoming > stored;
    else if constexpr (F == CompareFunc::NotEqual) return incoming != stored;
    else if constexpr (F == CompareFunc::GEqual) return incoming >= stored;
    else return incoming == incoming;
  }();
  if constexpr (std::is_arithmetic_v<T>) return bool(result);
  else return (T)result;  // a vector comparison gives signed lanes; same width, same bits
}

template <class Fn>
void withCompare(CompareFunc f, Fn&& fn) {
  switch (f) {
    case CompareFunc::Never: fn(std::integral_constant<CompareFunc, CompareFunc::Never>{}); return;
    case CompareFunc::Less: fn(std::integral_constant<CompareFunc, CompareFunc::Less>{}); return;
    case CompareFunc::Equal: fn(std::integral_constant<CompareFunc, CompareFunc::Equal>{}); return;
    case CompareFunc::LEqual: fn(std::integral_constant<CompareFunc, CompareFunc::LEqual>{}); return;
    case CompareFunc::Greater: fn(std::integral_constant<CompareFunc, CompareFunc::Greater>{}); return;
    case CompareFunc::NotEqual: fn(std::integral_constant<CompareFunc, CompareFunc::NotEqual>{}); return;
    case CompareFunc::GEqual: fn(std::integral_constant<CompareFunc, CompareFunc::GEqual>{}); return;
    case CompareFunc::Always: fn(std::integral_constant<CompareFunc, CompareFunc::Always>{}); return;
  }
}

}  // namespace shadowref
