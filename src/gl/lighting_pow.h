// The power function of the lighting model: the specular term max(R.V, 0)^n and the spot term
// max(cos, 0)^e ([Kuhn 2016, §2.3]; GL's shininess and spot exponent, both in [0, 128]).
//
// Why not std::pow: the C library's pow is free to differ between libraries and versions (glibc
// rewrote it in 2.28), so the same scene could give other bytes on another machine; and it is
// one call per fragment, the most expensive single step of per-pixel lighting. lightingPow is
// written with IEEE basic operations only (+, -, *, /, bit fields), so its bits depend on nothing
// but the input, and the same series run on four or eight values at once (lighting_pow_series.h).
// It is 2^(n·log2 x), with log2 from the atanh series and 2^r from its Taylor series, each taken
// to below double's rounding: relative error below 1e-13 against a correctly rounded pow (tests/gl/lighting_pow_test.cpp), far below
// the float colour buffer's 6e-8. Powers of two and x = 1 are exact.
#pragma once

namespace shadowref {

// x^n: x >= 0 (or NaN), n in [0, 128] (other n: std::pow). Special values as C's pow: x^0 = 1,
// +0^n = +0, -0^n = -0 for odd whole n (else +0), NaN^n = NaN. The fast executor's batch form,
// lightingPowColumn (exec/lighting_pow_column.h), gives every element these bits.
double lightingPow(double x, double n);

}  // namespace shadowref
