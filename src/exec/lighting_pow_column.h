// The lighting power of a whole batch at once: the fast executor's form of lightingPow
// (gl/lighting_pow.h), the reference's scalar definition, which it reproduces element by element.
#pragma once

namespace shadowref {

// x[i] = x[i]^n for i < count, each the bits lightingPow(x[i], n) gives (the same series,
// gl/lighting_pow_series.h, on every lane). The series are long chains of dependent multiplies
// and adds; one vector at a time waits on their latency, so this runs several vectors' chains
// side by side, eight lanes wide where the build has AVX-512.
void lightingPowColumn(double* x, int count, double n);

}  // namespace shadowref
