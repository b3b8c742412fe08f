#include "scene/scene_sections.h"

#include <cmath>

namespace shadowref {

const EnumNames<LightType>& lightTypeNames() {
  static const EnumNames<LightType> names{
      {"point", LightType::Point}, {"directional", LightType::Directional}, {"spot", LightType::Spot}};
  return names;
}

const EnumNames<SoftShape>& softShapeNames() {
  static const EnumNames<SoftShape> names{{"none", SoftShape::None},         {"square_x", SoftShape::SquareX},
                                          {"square_y", SoftShape::SquareY},  {"square_z", SoftShape::SquareZ},
                                          {"sphere14", SoftShape::Sphere14}, {"area16", SoftShape::AreaEdge16}};
  return names;
}

const EnumNames<ShadingModel>& shadingNames() {
  static const EnumNames<ShadingModel> names{{"gouraud", ShadingModel::Gouraud},
                                             {"per_pixel", ShadingModel::PerPixel}};
  return names;
}

const EnumNames<SilhouetteAlgorithm>& silhouetteNames() {
  static const EnumNames<SilhouetteAlgorithm> names{{"kuhn", SilhouetteAlgorithm::Kuhn},
                                                    {"yen_kwoon", SilhouetteAlgorithm::YenKwoon},
                                                    {"kilgard", SilhouetteAlgorithm::Kilgard},
                                                    {"lengyel", SilhouetteAlgorithm::Lengyel}};
  return names;
}

const EnumNames<MapFit>& mapFitNames() {
  static const EnumNames<MapFit> names{{"casters", MapFit::Casters}, {"scene", MapFit::Scene}};
  return names;
}

const EnumNames<ReceiverPlaneBias>& receiverPlaneBiasNames() {
  static const EnumNames<ReceiverPlaneBias> names{
      {"off", ReceiverPlaneBias::Off}, {"kernel", ReceiverPlaneBias::Kernel}, {"texel", ReceiverPlaneBias::Texel}};
  return names;
}

const EnumNames<DepthFormat>& depthFormatNames() {
  static const EnumNames<DepthFormat> names{{"float32", DepthFormat::Float32}, {"unorm24", DepthFormat::Unorm24}};
  return names;
}

namespace {

// A positive distance, or the word `infinite` (camera.far, a light's range).
double readDistanceOrInfinite(const YamlValue& v, const std::string& path) {
  if (v.isScalar() && v.scalar == "infinite") return kInfinity;
  if (v.isScalar() && (v.scalar == ".inf" || v.scalar == ".Inf" || v.scalar == ".INF"))
    failAt(v.at, path + ": write 'infinite' for an unbounded distance, not '" + v.scalar + "'");
  return readPositive(v, path);
}

const std::vector<Field<Scene>>& imageFields() {
  static const std::vector<Field<Scene>> fields{
      {"width", [](const YamlValue& v, Scene& s, const std::string& p, Provenance&) {
         // Each side in the documented range; the pixel count is checked with both sides known.
         s.width = readInt(v, p, 1, kMaxImageSide);
       }},
      {"height", [](const YamlValue& v, Scene& s, const std::string& p, Provenance&) {
         s.height = readInt(v, p, 1, kMaxImageSide);
       }},
      {"depth", [](const YamlValue& v, Scene& s, const std::string& p, Provenance&) {
         s.depthFormat = readEnum(v, p, depthFormatNames());
       }},
  };
  return fields;
}

const std::vector<Field<Camera>>& cameraFields() {
  static const std::vector<Field<Camera>> fields{
      {"eye", [](const YamlValue& v, Camera& c, const std::string& p, Provenance&) { c.eye = readVec3(v, p); }},
      {"target", [](const YamlValue& v, Camera& c, const std::string& p, Provenance&) { c.target = readVec3(v, p); }},
      {"up", [](const YamlValue& v, Camera& c, const std::string& p, Provenance&) { c.up = readDirection(v, p, "the up vector"); }},
      {"fov", [](const YamlValue& v, Camera& c, const std::string& p, Provenance&) {
         c.fovYDegrees = readNumber(v, p);
         if (!(c.fovYDegrees > 0.0 && c.fovYDegrees < 180.0))
           failAt(v.at, p + ": the vertical field of view must lie strictly between 0 and 180 degrees, got " + v.scalar);
       }},
      {"near", [](const YamlValue& v, Camera& c, const std::string& p, Provenance&) {
         c.nearPlane = readNumber(v, p);
         if (!(c.nearPlane > 0.0))
           failAt(v.at, p + ": the near plane distance must be greater than 0, got " + v.scalar);
       }},
      {"far", [](const YamlValue& v, Camera& c, const std::string& p, Provenance&) {
         c.farPlane = readDistanceOrInfinite(v, p);
       }},
  };
  return fields;
}

const std::vector<Field<Light>>& softFields() {
  static const std::vector<Field<Light>> fields{
      {"shape", [](const YamlValue& v, Light& l, const std::string& p, Provenance&) {
         l.soft = readEnum(v, p, softShapeNames());
       }},
      {"spacing", [](const YamlValue& v, Light& l, const std::string& p, Provenance&) {
         l.softSpacing = readPositive(v, p);
       }},
  };
  return fields;
}

const std::vector<Field<Light>>& lightFields() {
  static const std::vector<Field<Light>> fields{
      // A '.' would split the name in a -D key; the file's names are checked as the list is read,
      // this catches a -D that renames a light.
      {"name", [](const YamlValue& v, Light& l, const std::string& p, Provenance&) {
         l.name = readText(v, p);
         if (l.name.find('.') != std::string::npos)
           failAt(v.at, p + ": the name '" + l.name + "' must not contain '.' (it separates names in -D keys)");
       }},
      {"type", [](const YamlValue& v, Light& l, const std::string& p, Provenance&) {
         l.type = readEnum(v, p, lightTypeNames());
       }},
      {"position", [](const YamlValue& v, Light& l, const std::string& p, Provenance&) { l.position = readVec3(v, p); }},
      {"direction", [](const YamlValue& v, Light& l, const std::string& p, Provenance&) {
         l.direction = readDirection(v, p);
       }},
      {"color", [](const YamlValue& v, Light& l, const std::string& p, Provenance&) { l.color = readColor(v, p); }},
      {"range", [](const YamlValue& v, Light& l, const std::string& p, Provenance&) {
         l.range = readDistanceOrInfinite(v, p);
       }},
      {"spot_cutoff", [](const YamlValue& v, Light& l, const std::string& p, Provenance&) {
         l.spotCutoffDegrees = readNumberInRange(v, p, 0.0, 90.0);  // GL_SPOT_CUTOFF's range for a spot light
       }},
      {"spot_exponent", [](const YamlValue& v, Light& l, const std::string& p, Provenance&) {
         l.spotExponent = readNumberInRange(v, p, 0.0, 128.0);  // GL_SPOT_EXPONENT's range
       }},
      {"attenuation", [](const YamlValue& v, Light& l, const std::string& p, Provenance&) {
         glm::dvec3 a = readVec3(v, p);
         if (a.x < 0.0 || a.y < 0.0 || a.z < 0.0 || a == glm::dvec3(0.0))
           failAt(v.at, p + ": [constant, linear, quadratic] must be >= 0 and not all 0");
         l.attenuation = a;
       }},
      {"soft", [](const YamlValue& v, Light& l, const std::string& p, Provenance& where) {
         applyFields(v, p, softFields(), l, where);
       }},
  };
  return fields;
}

const std::vector<Field<Material>>& materialFields() {
  static const std::vector<Field<Material>> fields{
      {"ambient", [](const YamlValue& v, Material& m, const std::string& p, Provenance&) { m.ambient = readColor(v, p); }},
      {"diffuse", [](const YamlValue& v, Material& m, const std::string& p, Provenance&) { m.diffuse = readColor(v, p); }},
      {"specular", [](const YamlValue& v, Material& m, const std::string& p, Provenance&) {
         m.specular = readColor(v, p);
       }},
      {"shininess", [](const YamlValue& v, Material& m, const std::string& p, Provenance&) {
         m.shininess = readNumberInRange(v, p, 0.0, 128.0);  // GL_SHININESS's range
       }},
      {"shading", [](const YamlValue& v, Material& m, const std::string& p, Provenance&) {
         m.shading = readEnum(v, p, shadingNames());
       }},
      {"blinn", [](const YamlValue& v, Material& m, const std::string& p, Provenance&) { m.blinn = readBool(v, p); }},
  };
  return fields;
}

const std::vector<Field<ShadowSettings>>& shadowFields() {
  using S = ShadowSettings;
  static const std::vector<Field<S>> fields{
      {"method", [](const YamlValue& v, S& s, const std::string& p, Provenance&) {
         // Any name: the techniques are registered in src/shadow, which checks it (ShadowSettings).
         s.method = readText(v, p);
         s.methodAt = v.at;
       }},
      {"silhouette", [](const YamlValue& v, S& s, const std::string& p, Provenance&) {
         s.silhouette = readEnum(v, p, silhouetteNames());
       }},
      {"two_sided", [](const YamlValue& v, S& s, const std::string& p, Provenance&) { s.twoSidedStencil = readBool(v, p); }},
      {"wrap", [](const YamlValue& v, S& s, const std::string& p, Provenance&) { s.wrapOps = readBool(v, p); }},
      {"darken_composite", [](const YamlValue& v, S& s, const std::string& p, Provenance&) {
         s.darkenComposite = readBool(v, p);
       }},
      {"map_size", [](const YamlValue& v, S& s, const std::string& p, Provenance&) { s.mapSize = readInt(v, p, 8, 8192); }},
      {"offset_factor", [](const YamlValue& v, S& s, const std::string& p, Provenance&) {
         s.offsetFactor = readNumber(v, p);
       }},
      {"offset_units", [](const YamlValue& v, S& s, const std::string& p, Provenance&) {
         s.offsetUnits = readNumber(v, p);
       }},
      {"bias", [](const YamlValue& v, S& s, const std::string& p, Provenance&) { s.constantBias = readNumber(v, p); }},
      {"back_faces_only", [](const YamlValue& v, S& s, const std::string& p, Provenance&) {
         s.backFacesOnly = readBool(v, p);
       }},
      {"pcf", [](const YamlValue& v, S& s, const std::string& p, Provenance&) { s.pcf = readInt(v, p, 1, 15); }},
      {"receiver_plane_bias", [](const YamlValue& v, S& s, const std::string& p, Provenance&) {
         s.receiverPlaneBias = readEnum(v, p, receiverPlaneBiasNames());
       }},
      {"fit", [](const YamlValue& v, S& s, const std::string& p, Provenance&) { s.fit = readEnum(v, p, mapFitNames()); }},
      {"compare_fail", [](const YamlValue& v, S& s, const std::string& p, Provenance&) {
         s.compareFail = readNumberInRange(v, p, 0.0, 1.0);
       }},
      {"focus_region", [](const YamlValue& v, S& s, const std::string& p, Provenance&) {
         s.focusRegion = readNumber(v, p);
         if (!(s.focusRegion > 0.0 && s.focusRegion < 1.0))  // a fraction of the view depth ([Hempe 2004, §4.1])
           failAt(v.at, p + ": the focus region is a fraction of the view depth, between 0 and 1 exclusive");
       }},
  };
  return fields;
}

// A limit of the resource budget: a whole number from 1 up to 2^40 (far beyond any machine's
// memory: the bound only keeps the budget's sums from wrapping).
std::uint64_t readLimit(const YamlValue& v, const std::string& path) {
  constexpr double kMaxLimit = 1099511627776.0;  // 2^40
  const double x = readNumber(v, path);
  if (!(x >= 1.0 && x <= kMaxLimit) || x != std::floor(x))
    failAt(v.at, path + ": expected a whole number from 1 to 2^40 (1099511627776), got '" + v.scalar + "'");
  return static_cast<std::uint64_t>(x);
}

const std::vector<Field<ResourceLimits>>& limitFields() {
  using L = ResourceLimits;
  static const std::vector<Field<L>> fields{
      {"max_instances", [](const YamlValue& v, L& l, const std::string& p, Provenance&) { l.maxInstances = readLimit(v, p); }},
      {"max_triangles", [](const YamlValue& v, L& l, const std::string& p, Provenance&) { l.maxTriangles = readLimit(v, p); }},
      {"max_vertices", [](const YamlValue& v, L& l, const std::string& p, Provenance&) { l.maxVertices = readLimit(v, p); }},
  };
  return fields;
}

}  // namespace

void applyLimits(const YamlValue& map, ResourceLimits& limits, Provenance& where) {
  applyFields(map, "limits", limitFields(), limits, where);
}

void applyImage(const YamlValue& map, Scene& scene, Provenance& where) {
  applyFields(map, "image", imageFields(), scene, where);
}
void applyCamera(const YamlValue& map, Camera& camera, Provenance& where) {
  applyFields(map, "camera", cameraFields(), camera, where);
}
void applyLight(const YamlValue& map, Light& light, const std::string& path, Provenance& where) {
  applyFields(map, path, lightFields(), light, where);
  // A key the light's type does not read is an error, as an unknown key is: a directional light
  // has no position (it is at infinity), a point light no direction, and only a spot light a
  // cone. Checked against the type the light has after the map (the map may set it after the
  // key), for the keys this map wrote.
  if (!map.isMap()) return;
  for (const YamlEntry& e : map.entries) {
    const bool applies = e.key == "position"    ? light.type != LightType::Directional
                         : e.key == "direction" ? light.type != LightType::Point
                         : (e.key == "spot_cutoff" || e.key == "spot_exponent") ? light.type == LightType::Spot
                                                                                : true;
    if (applies) continue;
    std::vector<std::string_view> allowed;
    for (const Field<Light>& f : lightFields()) {
      const std::string_view k = f.key;
      if ((k == "position" && light.type == LightType::Directional) || (k == "direction" && light.type == LightType::Point) ||
          ((k == "spot_cutoff" || k == "spot_exponent") && light.type != LightType::Spot))
        continue;
      allowed.push_back(k);
    }
    const std::string type(enumName(lightTypeNames(), light.type));
    failAt(e.keyAt, "key '" + e.key + "' does not apply to the " + type + " light " + path + " (keys of a " + type +
                        " light: " + joinNames(allowed) + ")");
  }
}
void applyMaterial(const YamlValue& map, Material& material, const std::string& path, Provenance& where) {
  applyFields(map, path, materialFields(), material, where);
}
void applyShadow(const YamlValue& map, ShadowSettings& shadow, Provenance& where) {
  applyFields(map, "shadow", shadowFields(), shadow, where);
}

}  // namespace shadowref
