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
    line = line.substr(0, line.find('#'));
    std::istringstream in(line);
    std::string action, frame;
    ScriptEvent e;
    if (!(in >> frame)) continue;  // a blank line or only a comment
    try {
      e.frame = parseFrame(frame);
      if (!(in >> action)) throw std::invalid_argument("expected key, down, move, up, resize or wait after the frame");
      if (action == "key" || action == "keydown" || action == "keyup") {
        std::string key;
        if (!(in >> key)) throw std::invalid_argument("expected a key after '" + action + "'");
        e.action = action == "key" ? ScriptAction::Key : action == "keydown" ? ScriptAction::KeyDown : ScriptAction::KeyUp;
        e.key = parseKey(key);
      } else if (action == "wait") {
        std::string what;
        if (!(in >> what) || what != "advice") throw std::invalid_argument("expected 'advice' after 'wait'");
        e.action = ScriptAction::WaitAdvice;
      } else if (action == "resize") {
        e.action = ScriptAction::Resize;
        if (!(in >> e.x >> e.y) || e.x < 100 || e.y < 100 || e.x > 8192 || e.y > 8192)
          throw std::invalid_argument("expected a width and height between 100 and 8192 after 'resize'");
      } else {
        if (action == "down") e.action = ScriptAction::MouseDown;
        else if (action == "move") e.action = ScriptAction::MouseMove;
        else if (action == "up") e.action = ScriptAction::MouseUp;
        else if (action == "wheel") e.action = ScriptAction::Wheel;
        else throw std::invalid_argument("expected key, keydown, keyup, down, move, up, wheel, resize or wait, got '" + action + "'");
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
          if (button == "left") e.button = ScriptButton::Left;
          else if (button == "right") e.button = ScriptButton::Right;
          else if (button == "middle") e.button = ScriptButton::Middle;
          else if (button == "shift-left") e.button = ScriptButton::ShiftLeft;
          else throw std::invalid_argument("expected left, right, middle or shift-left, got '" + button + "'");
        }
      }
      std::string extra;
      if (in >> extra) throw std::invalid_argument("unexpected '" + extra + "' at the end of the line");
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
