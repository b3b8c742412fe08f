#include "tradeoffs/experiments.h"

namespace shadowref::bench {

const char* name(Reference reference) {
  switch (reference) {
    case Reference::HardLight: return "point";
    case Reference::AreaSquare: return "square";
    case Reference::AreaSphere: return "sphere";
  }
  return "?";
}

namespace {

class Builder {
 public:
  explicit Builder(const BenchSize& size) : size_(size) {}

  Experiment& add(std::string group, std::string scene, std::string variant, std::string method,
                  std::vector<std::string> overrides = {}, std::string plot = "") {
    Experiment e;
    e.group = std::move(group);
    e.scene = std::move(scene);
    e.variant = std::move(variant);
    e.method = std::move(method);
    e.overrides = {"image.width=" + std::to_string(size_.width), "image.height=" + std::to_string(size_.height)};
    for (std::string& o : overrides) e.overrides.push_back(std::move(o));
    e.plot = std::move(plot);
    list_.push_back(std::move(e));
    return list_.back();
  }
  void setSoftSpacing(const std::string& group, double s) {
    for (Experiment& e : list_)
      if (e.group == group) e.softSpacing = s;
  }
  std::vector<Experiment> take() { return std::move(list_); }

 private:
  BenchSize size_;
  std::vector<Experiment> list_;
};

// [Kuhn 2016, §5.4.1], first test: one light, more and more houses; random models (shadows only in
// the document) and one model, Haus01 (= model 0), with and without shadows.
void houses(Builder& b) {
  for (int n : {8, 16, 32, 64, 100}) {
    const std::string h = "generator.houses=" + std::to_string(n);
    for (const char* method : {"none", "zpass"}) {
      b.add("houses", "city", "houses=" + std::to_string(n) + " random", method, {h, "generator.models=random"});
      b.add("houses", "city", "houses=" + std::to_string(n) + " single", method,
            {h, "generator.models=single", "generator.model=0"});
    }
  }
}

// [Kuhn 2016, §5.4.1], second test: 16 houses of one model (Haus02 = model 1), 1 … 9 lights.
void lights(Builder& b) {
  for (int n = 1; n <= 9; ++n)
    for (const char* method : {"none", "zpass"})
      b.add("lights", "city", "lights=" + std::to_string(n), method,
            {"generator.houses=16", "generator.models=single", "generator.model=1",
             "generator.lights=" + std::to_string(n)});
}

// [Kuhn 2016, §5.4.2]: z-pass against z-fail (and auto) on the room, the pumpkins and a city of 64
// equal houses (Haus02). `none` shows what the shadows cost and how wrong their absence is.
void counting(Builder& b) {
  for (const char* method : {"none", "zpass", "zfail", "auto"}) {
    b.add("counting", "room", "room", method, {}, "room");
    b.add("counting", "pumpkins", "pumpkins", method, {}, "pumpkins");
    b.add("counting", "city", "city-64", method,
          {"generator.houses=64", "generator.models=single", "generator.model=1"}, "city-64");
  }
}

// [Kuhn 2016, §5.3 / §4.2] and [Hempe 2004, §4.2]: hard shadows against lights spread over a square
// (8 extra), a sphere (14 extra) and 16 lights on the edge of a square area light, accumulated
// ([Hempe 2004]) or as volumes. The light is lowered to y = 2.6 so that a sphere of radius 0.25
// around it stays in the room.
void soft(Builder& b) {
  const double s = 0.25;
  const std::string sp = std::to_string(s), side = std::to_string(2 * s);
  const std::vector<std::string> lowered = {"lights.ceiling.position=[0, 2.6, 0]"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> o = lowered;
    o.insert(o.end(), extra.begin(), extra.end());
    return o;
  };
  for (Reference ref : {Reference::AreaSquare, Reference::AreaSphere}) {
    const std::string refName = name(ref);
    b.add("soft", "room", "hard (vs " + refName + ")", "zfail", with({}), "soft-" + refName).reference = ref;
    b.add("soft", "room", "none (vs " + refName + ")", "none", with({}), "soft-" + refName).reference = ref;
  }
  b.add("soft", "room", "square_y 1+8", "zfail",
        with({"lights.ceiling.soft.shape=square_y", "lights.ceiling.soft.spacing=" + sp}), "soft-square")
      .reference = Reference::AreaSquare;
  b.add("soft", "room", "area16 volumes", "zfail",
        with({"lights.ceiling.soft.shape=area16", "lights.ceiling.soft.spacing=" + side}), "soft-square")
      .reference = Reference::AreaSquare;
  b.add("soft", "room", "hard shadow map", "shadowmap", with({}), "soft-square").reference = Reference::AreaSquare;
  b.add("soft", "room", "area16 accumulated", "shadowmap",
        with({"lights.ceiling.soft.shape=area16", "lights.ceiling.soft.spacing=" + side}), "soft-square")
      .reference = Reference::AreaSquare;
  b.add("soft", "room", "sphere14 1+14", "zfail",
        with({"lights.ceiling.soft.shape=sphere14", "lights.ceiling.soft.spacing=" + sp}), "soft-sphere")
      .reference = Reference::AreaSphere;
  b.setSoftSpacing("soft", s);
}

// [Hempe 2004, §6.1]: standard shadow map and TSM, 128² … 4096², on the outdoor scene.
void mapSize(Builder& b) {
  b.add("map_size", "outdoor", "no shadows", "none", {}, "outdoor");
  for (int n : {128, 256, 512, 1024, 2048, 4096})
    for (const char* method : {"shadowmap", "tsm"})
      b.add("map_size", "outdoor", std::to_string(n), method, {"shadow.map_size=" + std::to_string(n)}, "outdoor");
}

void pcf(Builder& b) {
  for (int k : {3, 5, 7}) {
    b.add("pcf", "outdoor", "1024 pcf " + std::to_string(k), "shadowmap",
          {"shadow.map_size=1024", "shadow.pcf=" + std::to_string(k)}, "outdoor");
    b.add("pcf", "outdoor", "256 pcf " + std::to_string(k), "tsm",
          {"shadow.map_size=256", "shadow.pcf=" + std::to_string(k)}, "outdoor");
  }
}

// Polygon offset ([Hempe 2004, §3.2]: the default 1.1 / 4), none, only units, stronger; back faces
// only; a constant bias in the comparison instead.
void bias(Builder& b) {
  struct Choice {
    const char* label;
    std::vector<std::string> o;
  };
  const std::vector<Choice> choices = {
      {"no offset", {"shadow.offset_factor=0", "shadow.offset_units=0"}},
      {"units 4 only", {"shadow.offset_factor=0", "shadow.offset_units=4"}},
      {"offset 4/16", {"shadow.offset_factor=4", "shadow.offset_units=16"}},
      {"back faces only", {"shadow.offset_factor=0", "shadow.offset_units=0", "shadow.back_faces_only=true"}},
      {"bias 0.001", {"shadow.offset_factor=0", "shadow.offset_units=0", "shadow.bias=0.001"}},
      {"bias 0.01", {"shadow.offset_factor=0", "shadow.offset_units=0", "shadow.bias=0.01"}},
  };
  for (const Choice& c : choices)
    for (const char* method : {"shadowmap", "tsm"}) {
      std::vector<std::string> o = c.o;
      o.push_back(std::string("shadow.map_size=") + (std::string(method) == "tsm" ? "256" : "1024"));
      b.add("bias", "outdoor", c.label, method, o, "outdoor");
    }
}

void depth(Builder& b) {
  for (const char* format : {"float32", "unorm24"}) {
    b.add("depth", "room", std::string("room ") + format, "zfail", {std::string("image.depth=") + format}, "room");
    b.add("depth", "pumpkins", std::string("pumpkins ") + format, "zfail", {std::string("image.depth=") + format},
          "pumpkins");
    b.add("depth", "outdoor", std::string("outdoor 1024 ") + format, "shadowmap",
          {std::string("image.depth=") + format, "shadow.map_size=1024"}, "outdoor");
  }
}

// P_inf against a finite far plane. Shadow volumes always render with P_inf ([Kuhn 2016, §3.3]), so
// the choice reaches the shadow-map methods only; the outdoor scene's own far plane is 300.
void farPlane(Builder& b) {
  for (const char* far : {"300", "infinite"})
    for (const char* method : {"shadowmap", "tsm"})
      b.add("far", "outdoor", std::string("far ") + far, method,
            {std::string("camera.far=") + far, std::string("shadow.map_size=") + (std::string(method) == "tsm" ? "256" : "1024")},
            "outdoor");
  for (const char* far : {"20", "infinite"})
    b.add("far", "room", std::string("room far ") + far, "shadowmap", {std::string("camera.far=") + far}, "room");
}

}  // namespace

std::vector<Experiment> allExperiments(const BenchSize& size) {
  Builder b(size);
  counting(b);
  soft(b);
  mapSize(b);
  pcf(b);
  bias(b);
  depth(b);
  farPlane(b);
  houses(b);
  lights(b);
  return b.take();
}

}  // namespace shadowref::bench
