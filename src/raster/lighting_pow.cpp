#include "raster/lighting_pow.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace shadowref {

namespace {

using v4l = int64_t __attribute__((vector_size(32)));

inline PowLanes splat(double x) { return PowLanes{x, x, x, x}; }  // (not {} + x: that turns -0 into +0)
inline v4l bitsOf(PowLanes x) {
  v4l b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}
inline PowLanes fromBits(v4l b) {
  PowLanes x;
  std::memcpy(&x, &b, sizeof x);
  return x;
}

// ln(m) = 2·atanh(f), f = (m − 1)/(m + 1) = 2f·(1 + f²/3 + f⁴/5 + …). With m in [√½, √2),
// |f| ≤ 0.1716 and f² ≤ 0.0295: the 13th term is below 2^-60 of the first.
constexpr int kLogTerms = 13;
constexpr std::array<double, kLogTerms> logCoefficients() {
  std::array<double, kLogTerms> c{};
  for (int k = 0; k < kLogTerms; ++k) c[size_t(k)] = 1.0 / double(2 * k + 1);
  return c;
}
constexpr std::array<double, kLogTerms> kLog = logCoefficients();

// 2^r = Σ (r·ln 2)^i / i!, |r| ≤ 0.5 (|r·ln 2| ≤ 0.347): the 15th term is below 2^-60.
constexpr int kExpTerms = 15;
constexpr double kLn2 = 0.6931471805599453094;
constexpr double kLog2e = 1.4426950408889634074;
constexpr std::array<double, kExpTerms> expCoefficients() {
  std::array<double, kExpTerms> c{};
  c[0] = 1.0;
  for (int i = 1; i < kExpTerms; ++i) c[size_t(i)] = c[size_t(i - 1)] * kLn2 / double(i);
  return c;
}
constexpr std::array<double, kExpTerms> kExp = expCoefficients();

// 2^k for whole k in [-1022, 1023], as bits.
inline PowLanes powerOfTwo(v4l k) { return fromBits((k + 1023) << 52); }

bool oddWhole(double n) { return std::floor(n) == n && std::fmod(n, 2.0) == 1.0; }

}  // namespace

PowLanes lightingPow(PowLanes x, double n) {
  if (!(n > 0.0 && n <= 128.0)) {
    PowLanes out;
    for (int lane = 0; lane < 4; ++lane) out[lane] = n == 0.0 ? 1.0 : std::pow(x[lane], n);
    return out;
  }
  // x = m · 2^e with m in [√½, √2); positive subnormals are scaled into the normal range first.
  const v4l tiny = (x > 0.0) & (x < 0x1p-1022);
  const PowLanes scaled = tiny ? x * 0x1p54 : x;
  const v4l bits = bitsOf(scaled);
  v4l e = ((bits >> 52) & 0x7ff) - 1023 - (tiny & 54);
  PowLanes m = fromBits((bits & 0x000fffffffffffff) | 0x3ff0000000000000);  // [1, 2)
  const v4l high = m > 1.4142135623730951;
  m = high ? m * 0.5 : m;
  e -= high;  // a true comparison is -1

  const PowLanes f = (m - 1.0) / (m + 1.0), f2 = f * f;
  PowLanes series = splat(kLog[kLogTerms - 1]);
  for (int k = kLogTerms - 2; k >= 0; --k) series = series * f2 + kLog[size_t(k)];
  const PowLanes log2m = ((2.0 * f) * series) * kLog2e;

  // n·log2 x = n·e + n·log2 m. For whole n the first part is a whole number, exactly, so the
  // fraction left for 2^r keeps every bit of the second.
  const PowLanes ne = n * __builtin_convertvector(e, PowLanes), nl = n * log2m;
  const PowLanes y = ne + nl;
  // Beyond ±1100 the result is 0 or inf whatever the fraction; NaN (from a NaN x) is fixed below.
  const PowLanes yk = y == y ? (y < -1100.0 ? splat(-1100.0) : (1100.0 < y ? splat(1100.0) : y)) : splat(0.0);
  PowLanes k = yk;
  for (int lane = 0; lane < 4; ++lane) k[lane] = std::nearbyint(yk[lane]);
  const PowLanes r = (ne - k) + nl;
  PowLanes p = splat(kExp[kExpTerms - 1]);
  for (int i = kExpTerms - 2; i >= 0; --i) p = p * r + kExp[size_t(i)];

  // p · 2^k in two steps, so a subnormal result is rounded once and an overflow becomes inf.
  const v4l kk = __builtin_convertvector(k, v4l);
  const v4l k1 = kk < -1022 ? v4l{} - 1022 : (kk > 1023 ? v4l{} + 1023 : kk);
  PowLanes result = (p * powerOfTwo(k1)) * powerOfTwo(kk - k1);
  result = y < -1100.0 ? splat(0.0) : (1100.0 < y ? splat(INFINITY) : result);

  // Special values, as C's pow has them: ±0, NaN, +inf; a negative x (never a lighting value)
  // goes to std::pow.
  const v4l zero = x == 0.0, passThrough = (x != x) | (x == INFINITY);
  if (zero[0] | zero[1] | zero[2] | zero[3]) {
    const double negativeZero = oddWhole(n) ? -0.0 : 0.0;
    result = zero ? (bitsOf(x) < 0 ? splat(negativeZero) : splat(0.0)) : result;
  }
  result = passThrough ? x : result;
  const v4l negative = x < 0.0;
  if (negative[0] | negative[1] | negative[2] | negative[3])
    for (int lane = 0; lane < 4; ++lane)
      if (negative[lane]) result[lane] = std::pow(x[lane], n);
  return result;
}

double lightingPow(double x, double n) { return lightingPow(PowLanes{x, 1.0, 1.0, 1.0}, n)[0]; }

}  // namespace shadowref
