#include "cli/version_info.h"

#include "build_info.h"
#include "build_revision.h"

namespace shadowref::cli {

const BuildInfo& buildInfo() {
  static const BuildInfo info{SHADOWREF_VERSION, SHADOWREF_REVISION, SHADOWREF_ISA_LEVEL, SHADOWREF_COMPILER,
                              SHADOWREF_BUILD_TYPE};
  return info;
}

std::string softwareName() {
  const BuildInfo& info = buildInfo();
  return "shadowref " + info.version + " (" + info.revision + ")";
}

std::string versionText() {
  const BuildInfo& info = buildInfo();
  return "shadowref " + info.version + "\nrevision: " + info.revision + "\nisa: " + info.isaLevel +
         "\ncompiler: " + info.compiler + "\nbuild type: " + (info.buildType.empty() ? "none" : info.buildType);
}

}  // namespace shadowref::cli
