#include "oracle/stencil_comparison.h"

#include <span>
#include <sstream>
#include <stdexcept>

namespace shadowref::oracle {

StencilComparison compareStencil(const OracleImage& oracle, std::span<const uint8_t> stencil, CountKind kind,
                                 size_t reportLimit) {
  if (stencil.size() != oracle.zpass.size()) throw std::invalid_argument("compareStencil: image sizes differ");
  StencilComparison result;
  std::ostringstream report;
  for (int y = 0; y < oracle.height; ++y)
    for (int x = 0; x < oracle.width; ++x) {
      const size_t i = oracle.index(x, y);
      if (oracle.nearEdge[i]) continue;
      ++result.compared;
      const int count = kind == CountKind::ZPass ? oracle.zpass[i] : oracle.zfail[i];
      const int expected = count & 0xFF;  // two's complement: -1 wraps to 255
      if (stencil[i] == expected) continue;
      if (result.mismatches++ < reportLimit)
        report << x << "," << y << ": stencil " << int(stencil[i]) << ", oracle " << count << " (hit instance "
               << oracle.hitInstance[i] << ")\n";
    }
  result.report = report.str();
  return result;
}

}  // namespace shadowref::oracle
