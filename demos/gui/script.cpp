#include "script.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace demo {

namespace {
struct KeyName {
  const char* name;
  unsigned char key;
};
constexpr KeyName keyNames[] = {{"space", ' '}, {"esc", 27}, {"enter", '\r'}, {"tab", '\t'}};

unsigned char parseKey(const std::string& word) {
  for (const KeyName& k : keyNames)
    if (word == k.name) return k.key;
  if (word.size() == 1 && word[0] > ' ' && word[0] < 127) return static_cast<unsigned char>(word[0]);
  throw std::invalid_argument("expected a key (one character, space, esc, enter or tab), got '" + word + "'");
}
// A line's first word: a frame number in [0, LLONG_MAX].
long long parseFrame(const std::string& word) {
  long long frame = 0;
  const char* end = word.data() + word.size();
  const auto [last, error] = std::from_chars(word.data(), end, frame);
  if (error == std::errc::result_out_of_range && word[0] != '-')
    throw std::invalid_argument("frame number " + word + " is out of range (at most " +
                                std::to_string(std::numeric_limits<long long>::max()) + ")");
  if (error != std::errc() || last != end || frame < 0)
    throw std::invalid_argument("expected a frame number >= 0 first, got '" + word + "'");
  return frame;
}

// The words after "<frame> <action>", one reader per kind of event; each
// throws std::invalid_argument saying what it expected.
void readKeyWords(std::istream& in, const std::string& action, ScriptEvent& e) {
  std::string key;
  if (!(in >> key)) throw std::invalid_argument("expected a key after '" + action + "'");
  e.key = parseKey(key);
}

void readWaitWords(std::istream& in, const std::string&, ScriptEvent&) {
  std::string what;
  if (!(in >> what) || what != "advice") throw std::invalid_argument("expected 'advice' after 'wait'");
}

void readResizeWords(std::istream& in, const std::string&, ScriptEvent& e) {
  if (!(in >> e.x >> e.y) || e.x < 100 || e.y < 100 || e.x > 8192 || e.y > 8192)
    throw std::invalid_argument("expected a width and height between 100 and 8192 after 'resize'");
}

// select scene | select <list> <index>: the lists of a scene file.
void readSelectWords(std::istream& in, const std::string&, ScriptEvent& e) {
  static const char* const lists[] = {"particles", "forces", "constraints", "colliders", "walls", "collisionEdges"};
  std::string list;
  if (!(in >> list)) throw std::invalid_argument("expected 'scene' or a list and an index after 'select'");
  if (list == "scene") return;
  if (std::find(std::begin(lists), std::end(lists), list) == std::end(lists))
    throw std::invalid_argument("expected scene, particles, forces, constraints, colliders, walls or collisionEdges, got '" + list + "'");
  if (!(in >> e.clicks) || e.clicks < 0) throw std::invalid_argument("expected an index >= 0 after '" + list + "'");
  e.target = list;
}

// edit selected|new|build <field> <value>: the value is the rest of the line.
void readEditWords(std::istream& in, const std::string&, ScriptEvent& e) {
  if (!(in >> e.target >> e.field) || (e.target != "selected" && e.target != "new" && e.target != "build"))
    throw std::invalid_argument("expected selected, new or build and a field name after 'edit'");
  std::getline(in, e.text);
  const std::size_t first = e.text.find_first_not_of(" \t"), last = e.text.find_last_not_of(" \t\r");
  if (first == std::string::npos) throw std::invalid_argument("expected a value after '" + e.field + "'");
  e.text = e.text.substr(first, last - first + 1);
}

struct ButtonName {
  const char* name;
  ScriptButton button;
};
constexpr ButtonName buttonNames[] = {{"left", ScriptButton::Left},
                                      {"right", ScriptButton::Right},
                                      {"middle", ScriptButton::Middle},
                                      {"shift-left", ScriptButton::ShiftLeft}};

ScriptButton parseButton(const std::string& word) {
  for (const ButtonName& b : buttonNames)
    if (word == b.name) return b.button;
  throw std::invalid_argument("expected left, right, middle or shift-left, got '" + word + "'");
}

// down, move, up and wheel: world|window x y, then a button or the wheel's clicks.
void readPointerWords(std::istream& in, const std::string& action, ScriptEvent& e) {
  std::string space, button;
  if (!(in >> space >> e.x >> e.y)) throw std::invalid_argument("expected world|window x y after '" + action + "'");
  if (!std::isfinite(e.x) || !std::isfinite(e.y)) throw std::invalid_argument("expected finite coordinates");
  if (space == "world") e.space = ScriptSpace::World;
  else if (space == "window") e.space = ScriptSpace::Window;
  else throw std::invalid_argument("expected world or window, got '" + space + "'");
  if (e.action == ScriptAction::Wheel) {
    if (!(in >> e.clicks) || e.clicks == 0 || std::abs(e.clicks) > 100)
      throw std::invalid_argument("expected wheel clicks, a nonzero integer within +-100");
  } else if (in >> button) {
    e.button = parseButton(button);
  }
}

// Every kind of event: the word that names it, its action and the reader of
// the words that follow.
struct EventKind {
  const char* word;
  ScriptAction action;
  void (*readWords)(std::istream& in, const std::string& action, ScriptEvent& e);
};
constexpr EventKind eventKinds[] = {
    {"key", ScriptAction::Key, readKeyWords},           {"keydown", ScriptAction::KeyDown, readKeyWords},
    {"keyup", ScriptAction::KeyUp, readKeyWords},       {"wait", ScriptAction::WaitAdvice, readWaitWords},
    {"resize", ScriptAction::Resize, readResizeWords},  {"down", ScriptAction::MouseDown, readPointerWords},
    {"move", ScriptAction::MouseMove, readPointerWords}, {"up", ScriptAction::MouseUp, readPointerWords},
    {"wheel", ScriptAction::Wheel, readPointerWords},    {"select", ScriptAction::Select, readSelectWords},
    {"edit", ScriptAction::Edit, readEditWords},
};

const EventKind& findEventKind(const std::string& action) {
  for (const EventKind& kind : eventKinds)
    if (action == kind.word) return kind;
  throw std::invalid_argument("expected key, keydown, keyup, down, move, up, wheel, resize, wait, select or edit, got '" +
                              action + "'");
}

// One line without its comment: false for a blank one, else the event in e.
bool parseLine(const std::string& line, ScriptEvent& e) {
  std::istringstream in(line);
  std::string action, frame;
  if (!(in >> frame)) return false;
  e.frame = parseFrame(frame);
  if (!(in >> action)) throw std::invalid_argument("expected key, down, move, up, resize or wait after the frame");
  const EventKind& kind = findEventKind(action);
  e.action = kind.action;
  kind.readWords(in, action, e);
  std::string extra;
  if (in >> extra) throw std::invalid_argument("unexpected '" + extra + "' at the end of the line");
  return true;
}
}  // namespace

std::vector<ScriptEvent> readScript(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
    throw std::invalid_argument(std::filesystem::exists(path, error)
                                    ? "script '" + path + "' is not a regular file"
                                    : "cannot read script file '" + path + "'");
  std::ifstream file(path);
  if (!file) throw std::invalid_argument("cannot read script file '" + path + "'");
  std::vector<ScriptEvent> events;
  int lineNumber = 0;
  for (std::string line; std::getline(file, line);) {
    ++lineNumber;
    ScriptEvent e;
    try {
      if (!parseLine(line.substr(0, line.find('#')), e)) continue;  // a blank line or only a comment
    } catch (const std::invalid_argument& err) {
      throw std::invalid_argument(path + ":" + std::to_string(lineNumber) + ": " + err.what());
    }
    events.push_back(e);
  }
  std::stable_sort(events.begin(), events.end(),
                   [](const ScriptEvent& a, const ScriptEvent& b) { return a.frame < b.frame; });
  return events;
}

}  // namespace demo
