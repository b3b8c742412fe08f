// Which build this is: what `shadowref --version` prints and what every image it writes records
// as its Software (see docs/outputs.md).
#pragma once

#include <string>

namespace shadowref::cli {

struct BuildInfo {
  std::string version;    // the CMake project version, "0.1.0"
  std::string revision;   // short git commit hash, "-dirty" when tracked files differed; or "unknown"
  std::string isaLevel;   // "x86-64-v4", "x86-64-v3" or "baseline": the vector level compiled for
  std::string compiler;   // CMake's compiler id and version, "GNU 12.2.0"
  std::string buildType;  // "Release", "Debug", ... (empty when none was given)
};

const BuildInfo& buildInfo();

// "shadowref 0.1.0 (78535ab)": the Software field of written images.
std::string softwareName();

// The --version text: "shadowref <version>" and one "name: value" line per other field.
std::string versionText();

}  // namespace shadowref::cli
