#include "exec/lighting_pow_column.h"

#include <algorithm>
#include <cstring>

#include "gl/lighting_pow_series.h"

namespace shadowref {

namespace {

using namespace pow_series;

// Vectors of kColumnLanes at a time, in groups of up to four.
#if defined(__AVX512F__)
constexpr int kColumnLanes = 8;
#else
constexpr int kColumnLanes = 4;
#endif

template <int G> void powGroup(double* x, int count, double n) {
  using Lanes = PowLanesOf<kColumnLanes>;
  Lanes v[G];
  if (count == G * kColumnLanes) {
    std::memcpy(v, x, sizeof v);
    powInRange<kColumnLanes, G>(v, n);
    std::memcpy(x, v, sizeof v);
    return;
  }
  double padded[G * kColumnLanes];
  std::fill(padded + count, padded + G * kColumnLanes, 1.0);  // lanes past the column: any value
  std::copy_n(x, count, padded);
  std::memcpy(v, padded, sizeof v);
  powInRange<kColumnLanes, G>(v, n);
  std::memcpy(padded, v, sizeof v);
  std::copy_n(padded, count, x);
}

}  // namespace

void lightingPowColumn(double* x, int count, double n) {
  if (!seriesRange(n)) {
    for (int i = 0; i < count; ++i) x[i] = outsideSeriesRange(x[i], n);
    return;
  }
  if (count <= 4) {  // a small triangle's batch: one vector of four, as the scalar definition takes
    PowLanesOf<4> v{1.0, 1.0, 1.0, 1.0};
    for (int i = 0; i < count; ++i) v[i] = x[i];
    powInRange<4, 1>(&v, n);
    for (int i = 0; i < count; ++i) x[i] = v[i];
    return;
  }
  constexpr int kGroup = 4 * kColumnLanes;
  int i = 0;
  for (; i + kGroup <= count; i += kGroup) powGroup<4>(x + i, kGroup, n);
  const int left = count - i;
  if (left > 3 * kColumnLanes) powGroup<4>(x + i, left, n);
  else if (left > 2 * kColumnLanes) powGroup<3>(x + i, left, n);
  else if (left > kColumnLanes) powGroup<2>(x + i, left, n);
  else if (left > 0) powGroup<1>(x + i, left, n);
}

}  // namespace shadowref
