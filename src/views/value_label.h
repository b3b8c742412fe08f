// The text of a legend's numbers, in the digits, '-' and '.' the built-in font draws.
#pragma once

#include <string>

namespace shadowref::views {

// lo and hi with as many decimals as tell them apart: three significant digits of the span
// hi - lo (0.99712 and 0.99891 for a span of 0.002; 2.1 and 17.8 for a span of 15), at most 8
// decimals; never an exponent. A value that is not finite is "-".
std::string rangeLabel(double value, double lo, double hi);

}  // namespace shadowref::views
