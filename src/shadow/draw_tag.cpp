#include "shadow/draw_tag.h"

namespace shadowref {

const char* name(DrawKind kind) {
  switch (kind) {
    case DrawKind::Ambient: return "ambient pass";
    case DrawKind::Lit: return "lit pass";
    case DrawKind::VolumeSides: return "volume side";
    case DrawKind::FrontCap: return "volume front cap";
    case DrawKind::BackCap: return "volume back cap";
    case DrawKind::Darken: return "darken pass";
    case DrawKind::Scene: return "scene";
    case DrawKind::ShadowMap: return "shadow-map pass";
    case DrawKind::VolumeView: return "volume view";
  }
  return "draw";
}

std::string describeDrawTag(uint32_t tag, const std::vector<Instance>& instances) {
  const int i = instanceOf(tag);
  std::string s = name(drawKindOf(tag));
  if (i >= 0 && size_t(i) < instances.size()) s += ", object '" + instances[size_t(i)].path + "'";
  return s;
}

}  // namespace shadowref
