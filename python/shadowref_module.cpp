// The Python module shadowref._shadowref: the library interface (include/shadowref/shadowref.h)
// and the ray-cast oracle for Python. The package's __init__.py builds the friendly layer (scenes
// from dicts, Frame) on these few functions; the .pyi beside it documents both for editors.
//
// Buffers cross into NumPy without a copy: each std::vector the renderer filled is moved to the
// heap and handed to a NumPy array together with a capsule that frees it when the last array (or
// view of it) goes. Rendering and the oracle release the GIL: other Python threads run meanwhile,
// and two threads may render at once (each frame has its own pipeline and threads).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "api/scene_impl.h"
#include "oracle/oracle.h"
#include "shadowref/shadowref.h"

namespace py = pybind11;
namespace api = shadowref::api;

namespace {

// A NumPy array that owns `values` (moved to the heap, freed by the capsule), in C order with the
// given shape. Read-only: the arrays are the frame's record, copy one to change it.
template <typename T>
py::array owningArray(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* heap = new std::vector<T>(std::move(values));
  py::capsule owner(heap, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  py::array_t<T> array(shape, heap->data(), owner);
  array.attr("flags").attr("writeable") = false;
  return array;
}

// Rows of a frame buffer: index y * width + x, row 0 at the bottom (as glReadPixels).
template <typename T>
py::object imageOrNone(std::vector<T>&& values, int width, int height, int channels = 1) {
  if (values.empty()) return py::none();
  std::vector<py::ssize_t> shape{height, width};
  if (channels > 1) shape.push_back(channels);
  return owningArray(std::move(values), shape);
}

// The part of a frame that stays in C++: what writeImage needs.
struct FrameImage {
  api::Frame frame;  // its buffers moved out into NumPy; `data` kept
  void write(const std::string& path) const {
    py::gil_scoped_release release;
    api::writeImage(frame, path);
  }
};

py::dict render(const api::Scene& scene, const std::string& method, const std::string& pipeline, int threads,
                bool stencilPerLight, bool visibility, bool shadowMaps, std::optional<std::pair<int, int>> history) {
  api::RenderOptions options;
  options.method = method;
  if (pipeline == "fast") options.pipeline = api::Pipeline::Fast;
  else if (pipeline == "reference") options.pipeline = api::Pipeline::Reference;
  else throw api::Error("pipeline: unknown pipeline '" + pipeline + "' (fast or reference)");
  if (threads < 0) throw api::Error("threads: " + std::to_string(threads) + " is negative (0: one per CPU)");
  options.threads = threads;
  options.stencilPerLight = stencilPerLight;
  options.visibility = visibility;
  options.shadowMaps = shadowMaps;
  if (history) {
    options.historyX = history->first;
    options.historyY = history->second;
  }
  auto image = std::make_unique<FrameImage>();
  {
    py::gil_scoped_release release;
    image->frame = api::render(scene, options);
  }
  api::Frame& f = image->frame;
  const int w = f.width, h = f.height;
  py::dict out;
  out["width"] = w;
  out["height"] = h;
  out["threads"] = f.threads;
  out["color"] = imageOrNone(std::move(f.color), w, h, 4);
  out["depth"] = imageOrNone(std::move(f.depth), w, h);
  out["eye_depth"] = imageOrNone(std::move(f.eyeDepth), w, h);
  out["stencil"] = imageOrNone(std::move(f.stencil), w, h);
  out["accumulation"] = imageOrNone(std::move(f.accumulation), w, h, 4);
  py::dict perLight;
  for (size_t i = 0; i < f.stencilPerLight.size(); ++i)
    perLight[py::str(f.lightNames[i])] = imageOrNone(std::move(f.stencilPerLight[i]), w, h);
  out["stencil_per_light"] = perLight;
  py::dict visible;
  for (size_t i = 0; i < f.visibility.size(); ++i)
    visible[py::str(f.visibilityNames[i])] = imageOrNone(std::move(f.visibility[i]), w, h);
  out["visibility"] = visible;
  py::dict maps;
  for (api::ShadowMap& m : f.shadowMaps) maps[py::str(m.name)] = imageOrNone(std::move(m.depth), m.width, m.height);
  out["shadow_maps"] = maps;
  py::dict stats;
  for (const auto& [name, value] : f.statistics) stats[py::str(name)] = value;
  out["stats"] = stats;
  py::dict passes;
  for (const auto& [name, ms] : f.passMilliseconds) passes[py::str(name)] = ms;
  out["pass_milliseconds"] = passes;
  out["warnings"] = f.warnings;
  py::list records;
  for (const api::FragmentRecord& r : f.history) {
    py::dict d;
    d["draw"] = r.draw;
    d["what"] = r.what;
    d["front"] = r.front;
    d["depth"] = r.depth;
    d["stored_depth"] = r.storedDepth;
    d["stencil_passed"] = r.stencilPassed;
    d["depth_passed"] = r.depthPassed;
    d["stencil_before"] = r.stencilBefore;
    d["stencil_after"] = r.stencilAfter;
    d["color_before"] = py::make_tuple(r.colorBefore[0], r.colorBefore[1], r.colorBefore[2], r.colorBefore[3]);
    d["color_after"] = py::make_tuple(r.colorAfter[0], r.colorAfter[1], r.colorAfter[2], r.colorAfter[3]);
    records.append(d);
  }
  out["history"] = records;
  out["image"] = py::cast(std::move(image));
  return out;
}

// The ray-cast oracle for one light of the scene (by index into its lights): what z-pass and
// z-fail would count and whether the light reaches the surface, per pixel, without the rasterizer.
py::dict castOracle(const api::Scene& scene, int light, int threads) {
  const shadowref::Scene& s = scene.impl().scene;
  if (light < 0 || size_t(light) >= s.lights.size())
    throw api::Error("oracle: light " + std::to_string(light) + " is not one of the scene's " +
                     std::to_string(s.lights.size()) + " lights");
  shadowref::oracle::OracleOptions options;
  options.threads = threads;
  shadowref::oracle::OracleImage image;
  {
    py::gil_scoped_release release;
    image = shadowref::oracle::castOracle(s, s.lights[size_t(light)], options);
  }
  const int w = image.width, h = image.height;
  py::dict out;
  out["light"] = s.lights[size_t(light)].name;
  out["zpass"] = imageOrNone(std::move(image.zpass), w, h);
  out["zfail"] = imageOrNone(std::move(image.zfail), w, h);
  out["lit"] = imageOrNone(std::move(image.lit), w, h);
  out["hit"] = imageOrNone(std::move(image.hitMask), w, h);
  out["near_edge"] = imageOrNone(std::move(image.nearEdge), w, h);
  out["hit_instance"] = imageOrNone(std::move(image.hitInstance), w, h);
  return out;
}

}  // namespace

PYBIND11_MODULE(_shadowref, m) {
  m.doc() = "shadowref's native layer; use the package `shadowref` (its __init__.py) instead.";
  // Bad input: its message is "file:line:col: message"; __init__.py makes it a SceneError with
  // the place split out.
  py::register_exception<api::Error>(m, "NativeError", PyExc_ValueError);

  py::class_<api::Scene>(m, "NativeScene")
      .def_static(
          "from_file",
          [](const std::string& path, const std::vector<std::string>& overrides) {
            py::gil_scoped_release release;
            return api::Scene::fromFile(path, overrides);
          },
          py::arg("path"), py::arg("overrides"))
      .def_static(
          "from_string",
          [](const std::string& yaml, const std::string& name, const std::vector<std::string>& overrides) {
            py::gil_scoped_release release;
            return api::Scene::fromString(yaml, name, overrides);
          },
          py::arg("yaml"), py::arg("name"), py::arg("overrides"))
      .def_property_readonly("width", &api::Scene::width)
      .def_property_readonly("height", &api::Scene::height)
      .def_property_readonly("method", &api::Scene::method)
      .def_property_readonly("lights", [](const api::Scene& s) {
        std::vector<std::string> names;
        for (const shadowref::Light& light : s.impl().scene.lights) names.push_back(light.name);
        return names;
      });

  py::class_<FrameImage>(m, "NativeFrameImage").def("write", &FrameImage::write, py::arg("path"));

  m.def("render", &render, py::arg("scene"), py::arg("method"), py::arg("pipeline"), py::arg("threads"),
        py::arg("stencil_per_light"), py::arg("visibility"), py::arg("shadow_maps"), py::arg("history"));
  m.def("oracle", &castOracle, py::arg("scene"), py::arg("light"), py::arg("threads"));
  m.def("version", &api::version);
  m.def("methods", &api::methods);
}
