#pragma once
// Overflow-safe size arithmetic for every place where sizes read from input meet: accessor and
// buffer-view bounds, index ranges, image dimensions, instance and triangle budgets. Each function
// returns std::nullopt instead of a wrapped-around value, so a caller cannot forget the check.
// Header-only so that the image library can use it without linking the scene library.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <type_traits>

namespace shadowref {

template <typename T>
  requires std::is_unsigned_v<T>
[[nodiscard]] constexpr std::optional<T> checkedAdd(T a, T b) {
  T sum{};
  if (__builtin_add_overflow(a, b, &sum)) return std::nullopt;
  return sum;
}

template <typename T>
  requires std::is_unsigned_v<T>
[[nodiscard]] constexpr std::optional<T> checkedMul(T a, T b) {
  T product{};
  if (__builtin_mul_overflow(a, b, &product)) return std::nullopt;
  return product;
}

// a * b + c, or nullopt when any step overflows.
template <typename T>
  requires std::is_unsigned_v<T>
[[nodiscard]] constexpr std::optional<T> checkedMulAdd(T a, T b, T c) {
  const std::optional<T> product = checkedMul(a, b);
  if (!product) return std::nullopt;
  return checkedAdd(*product, c);
}

// True when [offset, offset + length) lies inside [0, size): the test every read of a byte range
// taken from a file must pass before it touches memory. No addition can wrap.
[[nodiscard]] constexpr bool rangeInside(std::uint64_t offset, std::uint64_t length, std::uint64_t size) {
  return offset <= size && length <= size - offset;
}

}  // namespace shadowref
