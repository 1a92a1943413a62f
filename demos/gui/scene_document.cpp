#include "scene_document.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "particles/forces/angular_spring.h"
#include "particles/forces/polygon_area.h"
#include "scene_file/codecs.h"
#include "scene_file/json_parse.h"
#include "scene_file/scene_file.h"

namespace demo {

namespace {
// The lists whose objects name particles by index.
constexpr const char* referringLists[] = {"forces", "constraints", "collisionEdges"};

using scenes::toJson;

Eigen::Vector2d vec2(const Json& value) { return {value.at(0).get<double>(), value.at(1).get<double>()}; }

// Lists of elements inside one object, each element naming particles of
// its own (a face-area force's faces, a wind's edges): deleting a particle
// drops the elements that name it, not the whole object.
struct ElementList {
  const char* key;
  const char* indices;  // the element's field of indices, or null: the element is the array of indices
};
constexpr ElementList elementLists[] = {{"faces", "particles"}, {"edges", nullptr}};

Json* elementIndices(const ElementList& list, Json& element) {
  if (!list.indices) return &element;
  return element.is_object() && element.contains(list.indices) ? &element[list.indices] : nullptr;
}

// The fields of an object holding particle indices (see particlesOf).
std::vector<Json*> indexFields(const std::string& list, Json& object) {
  if (list == "collisionEdges") return {&object};
  std::vector<Json*> fields;
  if (!object.is_object()) return fields;
  for (const char* key : {"particle", "particles"})
    if (object.contains(key)) fields.push_back(&object[key]);
  for (const ElementList& elements : elementLists)
    if (object.contains(elements.key) && object[elements.key].is_array())
      for (Json& element : object[elements.key])
        if (Json* indices = elementIndices(elements, element)) fields.push_back(indices);
  return fields;
}

bool namesParticle(const Json& indices, int particle) {
  if (indices.is_number_integer()) return indices.get<int>() == particle;
  return indices.is_array() && std::find(indices.begin(), indices.end(), Json(particle)) != indices.end();
}

// Drops the elements of the object's element lists that name `particle`.
void dropElementsNaming(Json& object, int particle) {
  if (!object.is_object()) return;
  for (const ElementList& elements : elementLists) {
    if (!object.contains(elements.key) || !object[elements.key].is_array()) continue;
    Json kept = Json::array();
    for (Json& element : object[elements.key]) {
      const Json* indices = elementIndices(elements, element);
      if (!indices || !namesParticle(*indices, particle)) kept.push_back(std::move(element));
    }
    object[elements.key] = std::move(kept);
  }
}

// What an object's rest geometry becomes when a particle it names moves:
// one entry per type that has one (the format's field names).
struct RestFit {
  const char* type;
  void (*fit)(Json& object, const Json& document, int moved);
};
double armLength(const Json& object, const Json& document) {
  const Json& p = object.at("particles");
  return (particlePosition(document, p.at(0).get<int>()) - particlePosition(document, p.at(1).get<int>())).norm();
}
// The signed area of the ring of particles named by `ring` (an array of indices).
double ringAreaOf(const Json& ring, const Json& document) {
  std::vector<int> indices;
  for (const Json& index : ring) indices.push_back(index.get<int>());
  Eigen::VectorXd x(2 * ring.size());
  std::vector<int> local(indices.size());
  for (std::size_t k = 0; k < indices.size(); ++k) {
    x.segment<2>(2 * k) = particlePosition(document, indices[k]);
    local[k] = static_cast<int>(k);
  }
  return particles::ringArea(x, local);
}
const RestFit restFits[] = {
    {"spring", [](Json& o, const Json& d, int) { o["restLength"] = armLength(o, d); }},
    {"rod", [](Json& o, const Json& d, int) { o["length"] = armLength(o, d); }},
    {"angular-spring",
     [](Json& o, const Json& d, int) {
       const Json& p = o.at("particles");
       const Eigen::Vector2d zero = Eigen::Vector2d::Zero();
       o["restAngle"] = particles::angularSpringKernel(particlePosition(d, p.at(0).get<int>()),
                                                       particlePosition(d, p.at(1).get<int>()),
                                                       particlePosition(d, p.at(2).get<int>()), zero, zero, zero)
                            .angle;
     }},
    {"circular-wire",
     [](Json& o, const Json& d, int) {
       o["radius"] = (particlePosition(d, o.at("particle").get<int>()) - vec2(o.at("centre"))).norm();
     }},
    {"line", [](Json& o, const Json& d, int) { o["point"] = toJson(particlePosition(d, o.at("particle").get<int>())); }},
    {"pressure", [](Json& o, const Json& d, int) { o["restArea"] = ringAreaOf(o.at("particles"), d); }},
    {"face-area",
     [](Json& o, const Json& d, int moved) {
       for (Json& face : o.at("faces")) {
         const Json& ring = face.at("particles");
         if (std::find(ring.begin(), ring.end(), Json(moved)) != ring.end())
           face["restArea"] = ringAreaOf(ring, d);
       }
     }},
};

// The fields of each collider kind that are points (moved by translateCollider).
struct ColliderPoints {
  const char* type;
  std::vector<const char*> points;  // fields holding a point [x, y]
  const char* pointList;            // a field holding an array of points, or null
};
const ColliderPoints colliderPoints[] = {
    {"halfPlane", {"point"}, nullptr}, {"box", {"min", "max"}, nullptr}, {"polygon", {}, "vertices"},
    {"capsule", {"from", "to"}, nullptr}, {"disc", {"centre"}, nullptr},
};
}  // namespace

std::string ObjectRef::name() const { return isScene() ? "scene" : list + "[" + std::to_string(index) + "]"; }

Json emptyDocument() {
  Json document;
  document["name"] = "built scene";
  document["integrator"] = "rk4";
  document["dt"] = 0.002;
  document["view"] = {{"min", {-1.0, -1.0}}, {"max", {1.0, 1.0}}};
  document["particles"] = Json::array();
  document["forces"] = Json::array({{{"type", "gravity"}, {"acceleration", {0.0, -9.81}}}});
  document["constraints"] = Json::array();
  document["colliders"] = Json::array();
  return document;
}

Json documentOf(const scenes::Scene& scene) { return scenes::sceneToJson(scene); }

scenes::Scene buildDocument(const Json& document) {
  return scenes::readSceneDocument(document, documentName(document));
}

std::string documentFileText(const Json& document) { return scenes::writeScene(buildDocument(document)); }

std::string documentName(const Json& document) {
  const auto name = document.find("name");
  return name != document.end() && name->is_string() ? name->get<std::string>() : "built scene";
}

const Json& objectAt(const Json& document, const ObjectRef& ref) {
  if (ref.isScene()) return document;
  return document.at(ref.list).at(ref.index);
}

bool refersToObject(const Json& document, const ObjectRef& ref) {
  if (ref.isScene()) return true;
  const auto list = document.find(ref.list);
  return list != document.end() && list->is_array() && ref.index < list->size();
}

std::vector<int> particlesOf(const ObjectRef& ref, const Json& object) {
  std::vector<int> result;
  Json copy = object;
  for (const Json* field : indexFields(ref.list, copy)) {
    if (field->is_number_integer()) result.push_back(field->get<int>());
    if (field->is_array())
      for (const Json& index : *field)
        if (index.is_number_integer()) result.push_back(index.get<int>());
  }
  return result;
}

Eigen::Vector2d particlePosition(const Json& document, int particle) {
  return vec2(document.at("particles").at(static_cast<std::size_t>(particle)).at("position"));
}

int addParticle(Json& document, const Eigen::Vector2d& position, const Json& particleTemplate) {
  Json particle = {{"position", toJson(position)}};
  for (const auto& [key, value] : particleTemplate.items()) {
    if (key == "radius" && value.is_number() && value.get<double>() == 0.0) continue;  // no collision disc
    if (key == "pinned" && value == false) continue;
    particle[key] = value;
  }
  Json& list = document["particles"];
  list.push_back(std::move(particle));
  return static_cast<int>(list.size() - 1);
}

ObjectRef addObject(Json& document, const std::string& list, Json object) {
  Json& objects = document[list];
  if (!objects.is_array()) objects = Json::array();
  objects.push_back(std::move(object));
  return {list, objects.size() - 1};
}

void deleteObject(Json& document, const ObjectRef& ref) {
  if (ref.isScene() || !refersToObject(document, ref)) throw std::invalid_argument("nothing to delete");
  Json& objects = document[ref.list];
  objects.erase(objects.begin() + static_cast<long>(ref.index));
  if (ref.list != "particles") return;
  const int removed = static_cast<int>(ref.index);
  for (const char* listName : referringLists) {
    if (!document.contains(listName)) continue;
    Json kept = Json::array();
    for (Json& object : document[listName]) {
      dropElementsNaming(object, removed);
      const std::vector<int> named = particlesOf({listName, 0}, object);
      if (std::find(named.begin(), named.end(), removed) != named.end()) continue;
      for (Json* field : indexFields(listName, object)) {
        if (field->is_number_integer() && field->get<int>() > removed) *field = field->get<int>() - 1;
        if (field->is_array())
          for (Json& index : *field)
            if (index.is_number_integer() && index.get<int>() > removed) index = index.get<int>() - 1;
      }
      kept.push_back(std::move(object));
    }
    document[listName] = std::move(kept);
  }
}

void moveParticle(Json& document, int particle, const Eigen::Vector2d& position) {
  document.at("particles").at(static_cast<std::size_t>(particle))["position"] = toJson(position);
  for (const char* listName : {"forces", "constraints"}) {
    if (!document.contains(listName)) continue;
    for (Json& object : document[listName]) {
      const std::vector<int> named = particlesOf({listName, 0}, object);
      if (std::find(named.begin(), named.end(), particle) == named.end()) continue;
      const std::string type = object.value("type", "");
      for (const RestFit& entry : restFits)
        if (type == entry.type) entry.fit(object, document, particle);
    }
  }
}

void translateCollider(Json& document, const ObjectRef& ref, const Eigen::Vector2d& delta) {
  if (ref.list != "colliders" && ref.list != "walls") throw std::invalid_argument(ref.name() + " is not a collider");
  Json& collider = document.at(ref.list).at(ref.index);
  const std::string type = ref.list == "walls" ? "box" : collider.value("type", "");
  for (const ColliderPoints& kind : colliderPoints) {
    if (type != kind.type) continue;
    for (const char* field : kind.points) collider[field] = toJson(vec2(collider.at(field)) + delta);
    if (kind.pointList)
      for (Json& point : collider.at(kind.pointList)) point = toJson(vec2(point) + delta);
  }
}

void setField(Json& document, const ObjectRef& ref, const std::string& field, const Json& value) {
  if (field.empty()) throw std::invalid_argument("a field name is needed");
  Json& object = ref.isScene() ? document : document.at(ref.list).at(ref.index);
  if (!object.is_object()) throw std::invalid_argument(ref.name() + " has no named fields");
  if (value.is_null()) object.erase(field);
  else object[field] = value;
}

Json parseFieldValue(const std::string& text) {
  try {
    return scenes::parseJson(text);
  } catch (const scenes::SceneFileError&) {
    return Json(text);
  }
}

}  // namespace demo
