// The series of lightingPow (lighting_pow.h), written once for any number of lanes N and any
// number G of vectors worked side by side: every lane takes the same operations in the same order
// whatever N and G are, so a lane's bits are the same in every form. lighting_pow.cpp defines the
// reference's scalar lightingPow with it; the fast executor's column form (exec/lighting_pow_column.h)
// takes several wider vectors at once.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace shadowref::pow_series {

// N doubles in one GCC vector, and the int64 lanes of their comparisons (-1 true, 0 false) and
// bit fields. (A `vector_size` that depends on a template parameter is dropped by GCC 12 in an
// alias template, hence one specialisation per width.)
template <int N> struct LaneTypes;
template <> struct LaneTypes<4> {
  typedef double Values __attribute__((vector_size(32)));
  typedef int64_t Masks __attribute__((vector_size(32)));
};
template <> struct LaneTypes<8> {
  typedef double Values __attribute__((vector_size(64)));
  typedef int64_t Masks __attribute__((vector_size(64)));
};
template <int N> using PowLanesOf = typename LaneTypes<N>::Values;
template <int N> using MaskLanes = typename LaneTypes<N>::Masks;

template <int N> PowLanesOf<N> splat(double x) {
  PowLanesOf<N> v;
  for (int lane = 0; lane < N; ++lane) v[lane] = x;  // (not {} + x: that turns -0 into +0)
  return v;
}
template <int N> MaskLanes<N> bitsOf(PowLanesOf<N> x) {
  MaskLanes<N> b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}
template <int N> PowLanesOf<N> fromBits(MaskLanes<N> b) {
  PowLanesOf<N> x;
  std::memcpy(&x, &b, sizeof x);
  return x;
}
template <int N> bool anyLane(MaskLanes<N> m) {
  int64_t any = 0;
  for (int lane = 0; lane < N; ++lane) any |= m[lane];
  return any != 0;
}

// ln(m) = 2·atanh(f), f = (m − 1)/(m + 1) = 2f·(1 + f²/3 + f⁴/5 + …). With m in [√½, √2),
// |f| ≤ 0.1716 and f² ≤ 0.0295: the 13th term is below 2^-60 of the first.
inline constexpr int kLogTerms = 13;
constexpr std::array<double, kLogTerms> logCoefficients() {
  std::array<double, kLogTerms> c{};
  for (int k = 0; k < kLogTerms; ++k) c[size_t(k)] = 1.0 / double(2 * k + 1);
  return c;
}
inline constexpr std::array<double, kLogTerms> kLog = logCoefficients();

// 2^r = Σ (r·ln 2)^i / i!, |r| ≤ 0.5 (|r·ln 2| ≤ 0.347): the 15th term is below 2^-60.
inline constexpr int kExpTerms = 15;
inline constexpr double kLn2 = 0.6931471805599453094;
inline constexpr double kLog2e = 1.4426950408889634074;
constexpr std::array<double, kExpTerms> expCoefficients() {
  std::array<double, kExpTerms> c{};
  c[0] = 1.0;
  for (int i = 1; i < kExpTerms; ++i) c[size_t(i)] = c[size_t(i - 1)] * kLn2 / double(i);
  return c;
}
inline constexpr std::array<double, kExpTerms> kExp = expCoefficients();

// 2^k for whole k in [-1022, 1023], as bits.
template <int N> PowLanesOf<N> powerOfTwo(MaskLanes<N> k) { return fromBits<N>((k + 1023) << 52); }

inline bool oddWhole(double n) { return std::floor(n) == n && std::fmod(n, 2.0) == 1.0; }

// The series serve n in (0, 128]; any other n is C's pow, x^0 = 1 included.
inline bool seriesRange(double n) { return n > 0.0 && n <= 128.0; }
inline double outsideSeriesRange(double x, double n) { return n == 0.0 ? 1.0 : std::pow(x, n); }

// x^n for G vectors of N lanes, n in (0, 128]. Every step is written once and applied to the G
// vectors in turn: the same operations per lane whatever G is, with G independent chains for the
// processor to overlap.
template <int N, int G> void powInRange(PowLanesOf<N>* x, double n) {
  using Lanes = PowLanesOf<N>;
  using Mask = MaskLanes<N>;
  Lanes log2m[G], ne[G], nl[G], y[G], k[G], p[G];
  for (int g = 0; g < G; ++g) {
    // x = m · 2^e with m in [√½, √2); positive subnormals are scaled into the normal range first.
    const Mask tiny = (x[g] > 0.0) & (x[g] < 0x1p-1022);
    const Lanes scaled = tiny ? x[g] * 0x1p54 : x[g];
    const Mask bits = bitsOf<N>(scaled);
    Mask e = ((bits >> 52) & 0x7ff) - 1023 - (tiny & 54);
    Lanes m = fromBits<N>((bits & 0x000fffffffffffff) | 0x3ff0000000000000);  // [1, 2)
    const Mask high = m > 1.4142135623730951;
    m = high ? m * 0.5 : m;
    e -= high;  // a true comparison is -1
    ne[g] = n * __builtin_convertvector(e, Lanes);
    log2m[g] = m;  // m for now; its logarithm below
  }
  Lanes f[G], f2[G], series[G];
  for (int g = 0; g < G; ++g) {
    f[g] = (log2m[g] - 1.0) / (log2m[g] + 1.0);
    f2[g] = f[g] * f[g];
    series[g] = splat<N>(kLog[kLogTerms - 1]);
  }
  for (int t = kLogTerms - 2; t >= 0; --t)
    for (int g = 0; g < G; ++g) series[g] = series[g] * f2[g] + kLog[size_t(t)];
  for (int g = 0; g < G; ++g) {
    log2m[g] = ((2.0 * f[g]) * series[g]) * kLog2e;
    // n·log2 x = n·e + n·log2 m. For whole n the first part is a whole number, exactly, so the
    // fraction left for 2^r keeps every bit of the second.
    nl[g] = n * log2m[g];
    y[g] = ne[g] + nl[g];
    // Beyond ±1100 the result is 0 or inf whatever the fraction; NaN (from a NaN x) is fixed below.
    const Lanes yk = y[g] == y[g] ? (y[g] < -1100.0 ? splat<N>(-1100.0) : (1100.0 < y[g] ? splat<N>(1100.0) : y[g]))
                                  : splat<N>(0.0);
    k[g] = yk;
    for (int lane = 0; lane < N; ++lane) k[g][lane] = std::nearbyint(yk[lane]);
  }
  Lanes r[G];
  for (int g = 0; g < G; ++g) {
    r[g] = (ne[g] - k[g]) + nl[g];
    p[g] = splat<N>(kExp[kExpTerms - 1]);
  }
  for (int i = kExpTerms - 2; i >= 0; --i)
    for (int g = 0; g < G; ++g) p[g] = p[g] * r[g] + kExp[size_t(i)];

  for (int g = 0; g < G; ++g) {
    // p · 2^k in two steps, so a subnormal result is rounded once and an overflow becomes inf.
    const Mask kk = __builtin_convertvector(k[g], Mask);
    const Mask k1 = kk < -1022 ? Mask{} - 1022 : (kk > 1023 ? Mask{} + 1023 : kk);
    Lanes result = (p[g] * powerOfTwo<N>(k1)) * powerOfTwo<N>(kk - k1);
    result = y[g] < -1100.0 ? splat<N>(0.0) : (1100.0 < y[g] ? splat<N>(INFINITY) : result);

    // Special values, as C's pow has them: ±0, NaN, +inf; a negative x (never a lighting value)
    // goes to std::pow.
    const Lanes in = x[g];
    const Mask zero = in == 0.0, passThrough = (in != in) | (in == INFINITY);
    if (anyLane<N>(zero)) {
      const double negativeZero = oddWhole(n) ? -0.0 : 0.0;
      result = zero ? (bitsOf<N>(in) < 0 ? splat<N>(negativeZero) : splat<N>(0.0)) : result;
    }
    result = passThrough ? in : result;
    const Mask negative = in < 0.0;
    if (anyLane<N>(negative))
      for (int lane = 0; lane < N; ++lane)
        if (negative[lane]) result[lane] = std::pow(in[lane], n);
    x[g] = result;
  }
}

}  // namespace shadowref::pow_series
