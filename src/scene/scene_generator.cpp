#include "scene/scene_generator.h"

#include <climits>

#include "scene/generators.h"

namespace shadowref {

namespace {

// Limits keep a typo from asking for millions of objects; they cover the documents' experiments
// ([Kuhn 2016, §5.4.1]: up to 100 houses and 9 lights).
constexpr int kMaxHouses = 4096;
constexpr int kMaxCityLights = 64;
constexpr int kMaxTrees = 10000;

enum class GeneratorType { Room, Pumpkins, City, Outdoor };

const EnumNames<GeneratorType>& generatorNames() {
  static const EnumNames<GeneratorType> names{{"room", GeneratorType::Room},
                                              {"pumpkins", GeneratorType::Pumpkins},
                                              {"city", GeneratorType::City},
                                              {"outdoor", GeneratorType::Outdoor}};
  return names;
}

template <class O>
Field<O> setView(bool O::*member) {
  return {"set_view", [member](const YamlValue& v, O& o, const std::string& p, Provenance&) { o.*member = readBool(v, p); }};
}
template <class O>
Field<O> type() {
  return {"type", [](const YamlValue&, O&, const std::string&, Provenance&) {}};  // read before the options
}
int readSeed(const YamlValue& v, const std::string& p) { return readInt(v, p, 0, INT_MAX); }

const std::vector<Field<RoomOptions>>& roomFields() {
  static const std::vector<Field<RoomOptions>> fields{
      type<RoomOptions>(),
      {"size", [](const YamlValue& v, RoomOptions& o, const std::string& p, Provenance&) {
         o.size = readVec3(v, p);
         if (!(o.size.x > 0.0 && o.size.y > 0.0 && o.size.z > 0.0)) failAt(v.at, p + ": every side must be greater than 0");
       }},
      {"wall_thickness", [](const YamlValue& v, RoomOptions& o, const std::string& p, Provenance&) {
         o.wallThickness = readPositive(v, p);
       }},
      setView(&RoomOptions::setView),
  };
  return fields;
}

const std::vector<Field<PumpkinOptions>>& pumpkinFields() {
  static const std::vector<Field<PumpkinOptions>> fields{
      type<PumpkinOptions>(),
      // The lantern's face needs enough grid cells for eyes, mouth and tooth that do not touch.
      {"slices", [](const YamlValue& v, PumpkinOptions& o, const std::string& p, Provenance&) {
         o.slices = readInt(v, p, 18, 360);
       }},
      {"stacks", [](const YamlValue& v, PumpkinOptions& o, const std::string& p, Provenance&) {
         o.stacks = readInt(v, p, 16, 256);
       }},
      setView(&PumpkinOptions::setView),
  };
  return fields;
}

enum class CityModels { Random, Single };

const std::vector<Field<CityOptions>>& cityFields() {
  static const EnumNames<CityModels> models{{"random", CityModels::Random}, {"single", CityModels::Single}};
  static const std::vector<Field<CityOptions>> fields{
      type<CityOptions>(),
      {"houses", [](const YamlValue& v, CityOptions& o, const std::string& p, Provenance&) {
         o.houses = readInt(v, p, 1, kMaxHouses);
       }},
      {"models", [](const YamlValue& v, CityOptions& o, const std::string& p, Provenance&) {
         o.randomModels = readEnum(v, p, models) == CityModels::Random;
       }},
      {"model", [](const YamlValue& v, CityOptions& o, const std::string& p, Provenance&) {
         o.model = readInt(v, p, 0, kCityModelCount - 1);
       }},
      {"seed", [](const YamlValue& v, CityOptions& o, const std::string& p, Provenance&) {
         o.seed = static_cast<uint32_t>(readSeed(v, p));
       }},
      {"lights", [](const YamlValue& v, CityOptions& o, const std::string& p, Provenance&) {
         o.lights = readInt(v, p, 1, kMaxCityLights);
       }},
      {"framed_houses", [](const YamlValue& v, CityOptions& o, const std::string& p, Provenance&) {
         o.framedHouses = readInt(v, p, 0, kMaxHouses);
       }},
      setView(&CityOptions::setView),
  };
  return fields;
}

const std::vector<Field<OutdoorOptions>>& outdoorFields() {
  static const std::vector<Field<OutdoorOptions>> fields{
      type<OutdoorOptions>(),
      {"seed", [](const YamlValue& v, OutdoorOptions& o, const std::string& p, Provenance&) {
         o.seed = static_cast<uint32_t>(readSeed(v, p));
       }},
      {"trees", [](const YamlValue& v, OutdoorOptions& o, const std::string& p, Provenance&) {
         o.trees = readInt(v, p, 0, kMaxTrees);
       }},
      {"poles", [](const YamlValue& v, OutdoorOptions& o, const std::string& p, Provenance&) {
         o.poles = readInt(v, p, 0, kMaxTrees);
       }},
      {"size", [](const YamlValue& v, OutdoorOptions& o, const std::string& p, Provenance&) {
         o.size = readNumberInRange(v, p, 10.0, 100000.0);
       }},
      setView(&OutdoorOptions::setView),
  };
  return fields;
}

template <class O>
O readOptions(const YamlValue& section, const std::vector<Field<O>>& fields, Provenance& where) {
  O options;
  applyFields(section, "generator", fields, options, where);
  return options;
}

}  // namespace

YamlValue generatorShorthand(const YamlValue& scalar) {
  YamlValue map;
  map.kind = YamlValue::Kind::Map;
  map.at = scalar.at;
  map.entries.push_back(YamlEntry{"type", scalar.at, scalar});
  return map;
}

void runGenerator(const YamlValue& given, Scene& scene, Provenance& where) {
  const YamlValue section = given.isScalar() ? generatorShorthand(given) : given;
  if (!section.isMap())
    failAt(section.at, "generator: expected a name (room, pumpkins, city, outdoor) or {type: ..., options}");
  const YamlValue* typeValue = section.find("type");
  if (!typeValue) failAt(section.at, "generator: the key 'type' (room, pumpkins, city, outdoor) is missing");
  switch (readEnum(*typeValue, "generator.type", generatorNames())) {
    case GeneratorType::Room: addRoom(scene, readOptions(section, roomFields(), where)); break;
    case GeneratorType::Pumpkins: addPumpkins(scene, readOptions(section, pumpkinFields(), where)); break;
    case GeneratorType::City: addCity(scene, readOptions(section, cityFields(), where)); break;
    case GeneratorType::Outdoor: addOutdoor(scene, readOptions(section, outdoorFields(), where)); break;
  }
  // What the generator set is reported at the generator, unless the file sets it again.
  for (const char* made : {"image", "camera", "ambient", "background", "lights", "materials"}) where.record(made, section.at);
}

}  // namespace shadowref
