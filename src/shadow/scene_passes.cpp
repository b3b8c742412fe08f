#include "shadow/scene_passes.h"

#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>

namespace shadowref {

const RenderState& stateFor(const RenderState& state, const Instance& instance, RenderState& scratch) {
  if (!instance.mirrored) return state;
  scratch = state;
  scratch.frontFace = state.frontFace == FrontFace::CCW ? FrontFace::CW : FrontFace::CCW;
  return scratch;
}

PassStates::PassStates(const RenderState& state) : plain(state), mirrored(state) {
  mirrored.frontFace = state.frontFace == FrontFace::CCW ? FrontFace::CW : FrontFace::CCW;
}

namespace {

// Vertices [first, last) of a prepared instance: clip position, world position and normal (the
// other varyings zero), each constructed in place.
void prepareVertices(PreparedInstance& p, const glm::dmat3& normalMatrix, size_t first, size_t last) {
  const Instance& inst = *p.instance;
  const Mesh& mesh = *inst.mesh;
  for (size_t v = first; v < last; ++v) {
    const glm::dvec4 object(mesh.positions[v], 1.0);
    ClipVertex cv;
    cv.position = p.transform.toClip(object);
    const glm::dvec3 world = glm::dvec3(inst.world * object);
    const glm::dvec3 normal = glm::normalize(normalMatrix * mesh.normals[v]);
    for (int k = 0; k < 3; ++k) {
      cv.varyings[kVaryingPosition + k] = world[k];
      cv.varyings[kVaryingNormal + k] = normal[k];
    }
    placeVertex(p.vertices[v], cv);
  }
}

// Vertices are worked on in ranges of this many, the ranges of all items shared by the threads.
constexpr size_t kVertexRange = 1024;

}  // namespace

void forEachVertexRange(Pipeline* pipeline, std::span<const size_t> counts,
                        const std::function<void(size_t item, size_t first, size_t last)>& fn) {
  struct Range {
    size_t item, first, last;
  };
  std::vector<Range> ranges;
  for (size_t i = 0; i < counts.size(); ++i)
    for (size_t first = 0; first < counts[i]; first += kVertexRange)
      ranges.push_back({i, first, std::min(counts[i], first + kVertexRange)});
  auto run = [&](int r) {
    const Range& range = ranges[size_t(r)];
    fn(range.item, range.first, range.last);
  };
  if (pipeline) {
    pipeline->forEachIndependent(int(ranges.size()), run);
  } else {
    for (size_t r = 0; r < ranges.size(); ++r) run(int(r));
  }
}

std::vector<PreparedInstance> prepareInstances(const std::vector<Instance>& instances, const SceneView& view,
                                               Pipeline* pipeline) {
  std::vector<PreparedInstance> out(instances.size());
  std::vector<glm::dmat3> normalMatrices(instances.size());
  std::vector<size_t> counts(instances.size());
  for (size_t i = 0; i < instances.size(); ++i) {
    const Instance& inst = instances[i];
    PreparedInstance& p = out[i];
    p.instance = &inst;
    p.index = int(i);
    p.transform.modelView = view.view * inst.world;
    p.transform.projection = view.projection;
    normalMatrices[i] = glm::transpose(glm::inverse(glm::dmat3(inst.world)));
    counts[i] = inst.mesh->positions.size();
    p.vertices.resize(counts[i]);  // constructed by prepareVertices
    p.indices = triangleIndices(*inst.mesh);
  }
  forEachVertexRange(pipeline, counts, [&](size_t i, size_t first, size_t last) {
    prepareVertices(out[i], normalMatrices[i], first, last);
  });
  return out;
}

PhongLight toPhongLight(const Light& light) {
  PhongLight p;
  p.position = light.homogeneous();
  p.diffuse = light.color;
  p.specular = light.color;
  p.attenuation = light.attenuation;
  if (light.type == LightType::Spot) {
    p.spotDirection = light.direction;
    p.spotCosCutoff = std::cos(light.spotCutoffDegrees * std::numbers::pi / 180.0);
    p.spotExponent = light.spotExponent;
  }
  if (light.type == LightType::Directional) p.attenuation = glm::dvec3(1.0, 0.0, 0.0);
  return p;
}

PhongMaterial toPhongMaterial(const Material& m) {
  PhongMaterial p;
  p.ambient = m.ambient;
  p.diffuse = m.diffuse;
  p.specular = m.specular;
  p.shininess = m.shininess;
  p.blinn = m.blinn;
  return p;
}

bool withinRange(const Light& light, const Aabb& b) {
  if (std::isinf(light.range) || light.type == LightType::Directional) return true;
  const double r2 = light.range * light.range;
  auto inRange = [&](const glm::dvec3& p) {
    const glm::dvec3 d = p - light.position;
    return glm::dot(d, d) <= r2;
  };
  if (inRange(b.center())) return true;
  for (int i = 0; i < 8; ++i) {
    const glm::dvec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z);
    if (inRange(corner)) return true;
  }
  return false;
}

namespace {

// Instances of one material within range of the same lights: one lighting setup and one shader
// for all of them. The city's 129 instances have a handful of materials, so a pass makes a handful
// of setups and shaders instead of one of each — and their allocations, on the calling thread
// while the other threads wait — a draw. A shader is a function of its setup alone: the same
// bytes.
struct LightingGroup {
  size_t material = 0;
  std::vector<uint8_t> reached;  // per light of the pass: whether it is within range
  LightingSetup lighting;
  std::unique_ptr<FragmentShader> shader;
};

// An instance of a pass: its group, and for a Gouraud material its shaded vertices
// (PreparedInstance::shadedVertices).
struct LitInstance {
  const PreparedInstance* prepared = nullptr;
  size_t group = 0;
  ClipVertexBuffer* shadedVertices = nullptr;
};

// The shader of a group: its setup's constant ambient colour without lights, Gouraud's
// interpolation for a Gouraud material, per-pixel Phong otherwise.
std::unique_ptr<FragmentShader> groupShader(const LightingSetup& lighting, bool gouraud) {
  if (lighting.lights.empty()) {
    // Ambient only: shadePoint returns the ambient term for every point, so the rasterizer is told
    // it is a constant. Per pixel these are the same bits; for Gouraud every vertex has that
    // colour, and the constant is the exact value its interpolation would round (no interpolation).
    return std::make_unique<ConstantColorShader>(glm::dvec4(shadePoint(lighting, glm::dvec3(0.0), glm::dvec3(0.0)), 1.0));
  }
  // Gouraud: each vertex lit (drawLit, on the threads), the colour interpolated.
  if (gouraud) return std::make_unique<GouraudShader>();
  return std::make_unique<PerPixelLightingShader>(lighting);
}

// The group of instance `p` among `groups`, made if it is the first of its kind; `reached` is
// scratch of one entry per light.
size_t groupOf(const PreparedInstance& p, const Scene& scene, const SceneView& view, std::span<const Light> lights,
               bool includeAmbient, std::vector<uint8_t>& reached, std::vector<LightingGroup>& groups) {
  const size_t material = size_t(p.instance->material);
  for (size_t l = 0; l < lights.size(); ++l) reached[l] = withinRange(lights[l], p.instance->worldBounds);
  for (size_t g = 0; g < groups.size(); ++g)
    if (groups[g].material == material && groups[g].reached == reached) return g;
  LightingGroup& group = groups.emplace_back();
  group.material = material;
  group.reached = reached;
  const Material& m = scene.materials.at(material);
  LightingSetup& lighting = group.lighting;
  lighting.material = toPhongMaterial(m);
  lighting.globalAmbient = scene.ambient;
  lighting.includeAmbient = includeAmbient;
  lighting.eye = view.eye;
  for (size_t l = 0; l < lights.size(); ++l)
    if (reached[l]) lighting.lights.push_back(toPhongLight(lights[l]));
  if (includeAmbient || !lighting.lights.empty()) group.shader = groupShader(lighting, m.shading == ShadingModel::Gouraud);
  return groups.size() - 1;
}

// The vertices of `p` with each one's Gouraud colour in the colour varyings (gouraudVertexColor);
// without lights, the vertices as they are (the pass draws one constant colour).
void lightVertices(const PreparedInstance& p, const LightingSetup& lighting, ClipVertexBuffer& lit, size_t first,
                   size_t last) {
  for (size_t i = first; i < last; ++i) {
    ClipVertex& v = placeVertex(lit[i], p.vertices[i]);
    if (lighting.lights.empty()) continue;
    const glm::dvec3 pos(v.varyings[kVaryingPosition], v.varyings[kVaryingPosition + 1], v.varyings[kVaryingPosition + 2]);
    const glm::dvec3 n(v.varyings[kVaryingNormal], v.varyings[kVaryingNormal + 1], v.varyings[kVaryingNormal + 2]);
    const glm::dvec3 c = gouraudVertexColor(lighting, pos, n);
    for (int k = 0; k < 3; ++k) v.varyings[kVaryingColor + k] = c[k];
  }
}

void drawInstance(Pipeline& pipeline, const PassStates& states, const LitInstance& item, const FragmentShader& shader,
                  DrawKind kind) {
  const PreparedInstance& p = *item.prepared;
  DrawCall call;
  call.state = &states.of(*p.instance);
  call.indices = p.indices;
  call.tag = drawTag(kind, p.index);
  // A Gouraud material's passes draw its shaded vertices, the others `vertices`: each pass the
  // same array, with the same positions (a pipeline may find the triangles it set up before).
  call.vertices = item.shadedVertices ? std::span<const ClipVertex>(*item.shadedVertices) : std::span<const ClipVertex>(p.vertices);
  call.shader = &shader;
  pipeline.draw(call);
}

}  // namespace

void drawLit(Pipeline& pipeline, const RenderState& state, const Scene& scene, const SceneView& view,
             std::span<const PreparedInstance> prepared, std::span<const Light> lights, bool includeAmbient,
             DrawKind kind) {
  // The pass's shaders, states and vertices, alive until it ends below.
  std::vector<LightingGroup> groups;
  std::vector<LitInstance> items;
  items.reserve(prepared.size());
  std::vector<uint8_t> reached(lights.size());
  for (const PreparedInstance& p : prepared) {
    LitInstance item;
    item.prepared = &p;
    item.group = groupOf(p, scene, view, lights, includeAmbient, reached, groups);
    if (!groups[item.group].shader) continue;  // no light reaches it, and no ambient term
    if (scene.materials.at(groups[item.group].material).shading == ShadingModel::Gouraud) {
      item.shadedVertices = &p.shadedVertices;
      item.shadedVertices->resize(p.vertices.size());  // constructed by lightVertices
    }
    items.push_back(item);
  }
  // The Gouraud instances' vertices lit on all threads, before any draw.
  std::vector<size_t> counts(items.size());
  for (size_t i = 0; i < items.size(); ++i) counts[i] = items[i].shadedVertices ? items[i].shadedVertices->size() : 0;
  forEachVertexRange(&pipeline, counts, [&](size_t i, size_t first, size_t last) {
    lightVertices(*items[i].prepared, groups[items[i].group].lighting, *items[i].shadedVertices, first, last);
  });
  const PassStates states(state);
  for (const LitInstance& item : items) drawInstance(pipeline, states, item, *groups[item.group].shader, kind);
  pipeline.endPass();
}

void drawAmbient(Pipeline& pipeline, const RenderState& state, const Scene& scene, const SceneView& view,
                 std::span<const PreparedInstance> prepared, DrawKind kind) {
  drawLit(pipeline, state, scene, view, prepared, {}, true, kind);
}

}  // namespace shadowref
