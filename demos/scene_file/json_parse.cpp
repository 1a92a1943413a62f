#include "scene_file/json_parse.h"

#include <algorithm>
#include <cstring>
#include <unordered_set>
#include <vector>

#include "particles/cancel.h"
#include "scene_limits.h"

namespace scenes {

namespace {

// Builds the document from nlohmann's SAX events. Each open array or object
// is a frame; a member is appended at the end of its object's vector after a
// hash-set lookup of its key, so n keys cost O(n), not O(n²). Pointers to
// open containers stay valid: only the innermost container grows. The values
// are counted as they are placed, so that a file of tiny values ("[[],[],…]":
// three bytes of text, some 70 bytes of document each) is refused at
// SceneLimits::jsonValues before its document outgrows memory; and the
// cancel flag is watched (particles/cancel.h).
class DocumentBuilder : public nlohmann::json_sax<Json> {
 public:
  explicit DocumentBuilder(Json& root) : root_(root) {}

  bool null() override { return value(nullptr); }
  bool boolean(bool b) override { return value(b); }
  bool number_integer(number_integer_t x) override { return value(x); }
  bool number_unsigned(number_unsigned_t x) override { return value(x); }
  bool number_float(number_float_t x, const string_t&) override { return value(x); }
  bool string(string_t& s) override { return value(std::move(s)); }
  bool binary(binary_t& b) override { return value(Json::binary(std::move(b))); }

  bool start_object(std::size_t) override { return open(Json::object()); }
  bool key(string_t& k) override {
    Frame& frame = frames_.back();
    frame.key = k;
    if (!frame.keys.insert(k).second)
      throw SceneFileError(path() + ": duplicate key (each key may appear once in an object)");
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(Json::array()); }
  bool end_array() override { return close(); }

  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& e) override {
    // nlohmann's what() reads "[json.exception.parse_error.101] parse error at ...".
    const char* detail = std::strstr(e.what(), "] ");
    throw JsonSyntaxError(detail ? detail + 2 : e.what(), position);
  }

 private:
  struct Frame {
    Json* container;
    std::unordered_set<std::string> keys;  // objects: the keys so far
    std::string key;                       // objects: the member being read
    std::size_t index = 0;                 // arrays: the element being read
  };

  // Places v where the next value goes and returns it.
  Json* place(Json&& v) {
    if (++values_ > SceneLimits::jsonValues) {
      if (!frames_.empty() && frames_.back().container->is_array())
        frames_.back().index = frames_.back().container->size();  // the path of v
      throw SceneFileError(path() + ": expected at most " + std::to_string(SceneLimits::jsonValues) +
                           " JSON values in a scene file (numbers, strings, booleans, nulls, arrays and objects), "
                           "got more");
    }
    if (cancel_.poll()) throw particles::Cancelled();
    if (frames_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    Frame& frame = frames_.back();
    if (frame.container->is_array()) {
      auto& array = *frame.container->get_ptr<Json::array_t*>();
      array.push_back(std::move(v));
      frame.index = array.size() - 1;
      return &array.back();
    }
    auto& members = static_cast<Json::object_t::Container&>(*frame.container->get_ptr<Json::object_t*>());
    members.emplace_back(frame.key, std::move(v));
    return &members.back().second;
  }
  bool value(Json&& v) {
    place(std::move(v));
    return true;
  }
  bool open(Json&& container) {
    if (static_cast<int>(frames_.size()) >= SceneLimits::nestingDepth) {
      // The path of the container being opened, then the limit.
      place(Json());
      throw SceneFileError(path() + ": expected at most " + std::to_string(SceneLimits::nestingDepth) +
                           " levels of nested arrays and objects, got more");
    }
    frames_.push_back({place(std::move(container)), {}, {}, 0});
    return true;
  }
  bool close() {
    frames_.pop_back();
    return true;
  }

  // The JSON path of the value being read: "$", then a member or index per open frame.
  std::string path() const {
    std::string p = "$";
    for (const Frame& frame : frames_)
      p += frame.container->is_array() ? "[" + std::to_string(frame.index) + "]" : memberPath(frame.key);
    return p;
  }

  Json& root_;
  std::vector<Frame> frames_;
  long long values_ = 0;
  particles::CancelPoll cancel_{4096};
};

}  // namespace

Json parseJson(const std::string& text) {
  Json document;
  DocumentBuilder builder(document);
  // nlohmann's lexer ends the input at a NUL byte, so that "{...}\0garbage"
  // would load: a NUL anywhere (JSON never holds one raw) is a syntax error.
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos) {
    const std::size_t lineStart = text.rfind('\n', nul);
    const std::size_t line = 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + nul, '\n'));
    const std::size_t column = nul - (lineStart == std::string::npos ? 0 : lineStart + 1) + 1;
    throw JsonSyntaxError("parse error at line " + std::to_string(line) + ", column " + std::to_string(column) +
                              ": a NUL byte (JSON text holds none; trailing bytes after the document are refused)",
                          nul);
  }
  Json::sax_parse(text, &builder);
  return document;
}

}  // namespace scenes
