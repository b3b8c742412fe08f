// What a call under test throws, for tests of error messages.
#pragma once

#include <exception>
#include <functional>
#include <string>

#include <catch2/catch.hpp>

#include "scene/scene_error.h"
#include "scene/scene_loader.h"

namespace shadowref::testing {

// The message of the exception `fn` throws; "(no error)" when it throws none.
inline std::string messageOf(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

// The message of the SceneError that loading `yaml` as the file "t.yaml" throws; "(no error)"
// when it loads.
inline std::string yamlErrorOf(const std::string& yaml, const LoadOptions& options = {}) {
  try {
    loadSceneFromString(yaml, "t.yaml", options);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

// The SceneError a call throws; fails the test if it throws none.
template <class F>
SceneError sceneErrorOf(F&& f) {
  try {
    f();
  } catch (const SceneError& e) {
    return e;
  }
  FAIL("no SceneError thrown");
  throw;  // unreachable: FAIL throws
}

}  // namespace shadowref::testing
