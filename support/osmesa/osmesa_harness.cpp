#include "osmesa/osmesa_harness.h"

#include <map>
#include <memory>

namespace shadowref::conformance {

trace::OsmesaContext& mesaContext(int width, int height) {
  static std::map<std::pair<int, int>, std::unique_ptr<trace::OsmesaContext>> contexts;
  auto& slot = contexts[{width, height}];
  if (!slot) slot = std::make_unique<trace::OsmesaContext>(width, height);
  slot->makeCurrent();
  trace::setFixedFunctionDefaults();
  return *slot;
}

std::string mesaRenderer() { return mesaContext(8, 8).renderer(); }

std::string mesaDriverName() {
  const std::string r = mesaRenderer();
  for (const char* known : {"softpipe", "llvmpipe"})
    if (r.find(known) != std::string::npos) return known;
  return r;
}

}  // namespace shadowref::conformance
