#pragma once
// Parsing a scene file's text into a Json document with the limits a hostile
// file needs: nesting at most SceneLimits::nestingDepth deep, every key of an
// object unique, and time linear in the size of the text (nlohmann's own DOM
// parser inserts each member of an ordered_json object by a linear search for
// its key, which is quadratic in the number of keys).
#include <string>

#include "scene_file/json_node.h"

namespace scenes {

// The text is not JSON: what() is nlohmann's message without its exception id
// ("parse error at line 4, column 3: ..."), byte where parsing stopped.
class JsonSyntaxError : public SceneFileError {
 public:
  JsonSyntaxError(const std::string& message, std::size_t byte) : SceneFileError(message), byte(byte) {}
  std::size_t byte;
};

// Throws JsonSyntaxError, or SceneFileError "<JSON path>: <reason>" for a
// value nested too deep or a key that appears twice in one object.
Json parseJson(const std::string& text);

}  // namespace scenes
