#pragma once
// A scene being built in the demo's build mode, held as its scene-file
// document (demos/scenes/FORMAT.md). Every edit is an edit of that JSON; the
// scene on screen, the file saved and the scene the runner loads from it are
// all read by the one scene-file reader, so an edit the reader refuses (a
// particle placed inside a collider, a zero rest length) is refused before it
// changes anything, with the reader's one-line message. No OpenGL here.
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "scene.h"
#include "scene_file/json_node.h"

namespace demo {

using scenes::Json;

// One object of a document: element `index` of one of its lists
// ("particles", "forces", "constraints", "colliders", "walls",
// "collisionEdges"), or the scene itself (its top-level fields) when list is empty.
struct ObjectRef {
  std::string list;
  std::size_t index = 0;

  bool isScene() const { return list.empty(); }
  bool operator==(const ObjectRef& other) const { return list == other.list && index == other.index; }
  bool operator!=(const ObjectRef& other) const { return !(*this == other); }
  std::string name() const;  // "particles[3]", or "scene"
};

// A scene with nothing in it: gravity of 9.81 m/s² downward, RK4 at dt 2 ms,
// the view [-1, 1]², named "built scene".
Json emptyDocument();

// The document of a built scene, in its present state (scenes::sceneToJson).
Json documentOf(const scenes::Scene& scene);

// Reads the document as the scene-file reader reads a file's: throws
// scenes::SceneFileError with its one-line message for anything it refuses.
scenes::Scene buildDocument(const Json& document);

// The scene file the document saves as: the runner's export writer
// (scenes::writeScene) over the scene the document reads as, so a saved file
// loads back to the same scene bit for bit.
std::string documentFileText(const Json& document);

// The document's name, as a label for the screen.
std::string documentName(const Json& document);

// The object a reference names; std::out_of_range when there is none.
const Json& objectAt(const Json& document, const ObjectRef& ref);
bool refersToObject(const Json& document, const ObjectRef& ref);

// The particle indices an object names: a collision edge's pair, or an
// object's "particle" or "particles" field (the format's only fields that
// hold indices); none for a particle, a collider or a global force.
std::vector<int> particlesOf(const ObjectRef& ref, const Json& object);

// A particle's position in the document.
Eigen::Vector2d particlePosition(const Json& document, int particle);

// --- edits: each changes the document in place --------------------------------
// Adds a particle at `position` with the fields of `particleTemplate` (mass,
// pinned, radius; a radius of 0 makes no collision disc); returns its index.
int addParticle(Json& document, const Eigen::Vector2d& position, const Json& particleTemplate);
// Appends an object to one of the lists; returns its reference.
ObjectRef addObject(Json& document, const std::string& list, Json object);
// Deletes an object; a particle takes every force, constraint and collision
// edge naming it along, and the indices above it move down by one.
void deleteObject(Json& document, const ObjectRef& ref);
// Moves a particle; the springs, rods, angle springs, wires and lines on it
// take their rest length, length, rest angle, radius or point from the new
// position, so the scene starts at rest in the shape drawn.
void moveParticle(Json& document, int particle, const Eigen::Vector2d& position);
// Moves a collider (its points; a half-plane's normal is unchanged).
void translateCollider(Json& document, const ObjectRef& ref, const Eigen::Vector2d& delta);
// Sets one field of an object or of the scene; a null value removes it.
void setField(Json& document, const ObjectRef& ref, const std::string& field, const Json& value);

// A field value as typed: JSON text (0.5, [0, 1], true, "root"), or else the
// text itself as a string (root, my scene).
Json parseFieldValue(const std::string& text);

}  // namespace demo
