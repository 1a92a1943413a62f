#pragma once
// Scripted input: timed key and mouse events, read from a text file and fed
// to the application through the same handlers as GLUT's callbacks.
//
// One event per line; '#' starts a comment:
//   <frame> key <k>                          k: one character, or space, esc, enter, tab
//   <frame> keydown|keyup <k>                a key held over frames (space + drag pans)
//   <frame> down|move|up world|window <x> <y> [left|right|middle|shift-left]
//   <frame> wheel world|window <x> <y> <clicks>   clicks > 0 zoom in, < 0 out
//   <frame> resize <width> <height>          asks the window system for a new size
//   <frame> wait advice                      holds the script while the panel's advice runs
//   <frame> select scene|<list> <index>      build mode: selects an object, as its entry in the panel's list
//   <frame> edit selected|new|build <field> <value>   build mode: sets a field, as the panel's fields do
// <frame> counts frames from 0; events of frame k are handled before frame k
// steps and draws. While a wait holds, the script's clock stands still (the
// demo keeps drawing): every later event comes that many frames later. world coordinates are mapped to pixels through the first
// pane's view at that frame; window coordinates are pixels, origin top-left.
#include <string>
#include <vector>

namespace demo {

enum class ScriptAction { Key, KeyDown, KeyUp, MouseDown, MouseMove, MouseUp, Wheel, Resize, WaitAdvice, Select, Edit };
enum class ScriptSpace { World, Window };
enum class ScriptButton { Left, Right, Middle, ShiftLeft };

struct ScriptEvent {
  long long frame = 0;
  ScriptAction action = ScriptAction::Key;
  unsigned char key = 0;
  ScriptSpace space = ScriptSpace::Window;
  double x = 0.0, y = 0.0;
  ScriptButton button = ScriptButton::Left;
  int clicks = 0;  // wheel
  // select: target the list ("" for the scene), clicks the index; edit:
  // target selected|new|build, the field and the value's text (the rest of the line).
  std::string target, field, text;
};

// Reads a script; throws std::invalid_argument naming the file, line and what
// was expected, or for a path that is not a regular file (a directory, a FIFO).
std::vector<ScriptEvent> readScript(const std::string& path);

}  // namespace demo
