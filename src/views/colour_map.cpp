#include "views/colour_map.h"

#include <algorithm>
#include <cmath>

namespace shadowref::views {

namespace {

// [Zucker 2020]: c0 + t (c1 + t (c2 + ... + t c6)) per channel, fitted to matplotlib's 256-entry
// viridis table [van der Walt & Smith 2015]; within about 1/255 of it.
constexpr double kViridis[7][3] = {
    {0.2777273272234177, 0.005407344544966578, 0.3340998053353061},
    {0.1050930431085774, 1.404613529898575, 1.384590162594685},
    {-0.3308618287255563, 0.214847559468213, 0.09509516302823659},
    {-4.634230498983486, -5.799100973351585, -19.33244095627987},
    {6.228269936347081, 14.17993336680509, 56.69055260068105},
    {4.776384997670288, -13.74514537774601, -65.35303263337234},
    {-5.435455855934631, 4.645852612178535, 26.3124352495832},
};

uint8_t toByte(double v) { return uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

}  // namespace

Rgb8 viridis(double t) {
  t = t >= 0.0 ? std::min(t, 1.0) : 0.0;  // also NaN -> 0
  Rgb8 out{};
  for (int c = 0; c < 3; ++c) {
    double v = kViridis[6][c];
    for (int k = 5; k >= 0; --k) v = kViridis[k][c] + t * v;
    out[size_t(c)] = toByte(v);
  }
  return out;
}

}  // namespace shadowref::views
