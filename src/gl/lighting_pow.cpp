#include "gl/lighting_pow.h"

#include "gl/lighting_pow_series.h"

namespace shadowref {

double lightingPow(double x, double n) {
  using namespace pow_series;
  if (!seriesRange(n)) return outsideSeriesRange(x, n);
  PowLanesOf<4> lanes{x, 1.0, 1.0, 1.0};
  powInRange<4, 1>(&lanes, n);
  return lanes[0];
}

}  // namespace shadowref
