// The explorer's "save": the scene file with the page's state written into it, so that loading the
// saved file gives the scene the state's -D overrides give.
#pragma once

#include <string>
#include <vector>

namespace shadowref::explore {

// `source` is the scene file's text (YAML); `overrides` are "key=value" as -D takes them, with
// lights named (lights.NAME.KEY; lights.N.KEY is written as light N of `lightNames`). image.*,
// camera.*, shadow.*, ambient, background, generator.* and lights.* go into their sections; a
// light the file's list does not hold is added under its name, which changes a generator's light of
// that name. What a file cannot say (removing a generator's light, nodes, materials, meshes, limits)
// is kept as a comment with the -D that does it. Throws std::runtime_error when `source` is not
// a YAML map.
std::string sceneWithOverrides(const std::string& source, const std::vector<std::string>& overrides,
                               const std::vector<std::string>& lightNames, const std::string& from);

}  // namespace shadowref::explore
