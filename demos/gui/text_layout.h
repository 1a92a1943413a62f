#pragma once
// Text laid out for the bars around the panes (overlay.cpp): lines of
// coloured pieces wrapped at spaces to a width, and a bar's wrapped lines
// kept from one frame to the next while its text and width stay the same,
// so that a frame measures only the text that changed (text widths are the
// costly part of laying it out).
#include <imgui.h>

#include <string>
#include <vector>

namespace demo {

// A line of text in a bar: pieces of text in their colours, one after
// another; a piece marked whole is never broken across lines.
struct Piece {
  std::string text;
  ImU32 colour;
  bool whole = false;
  bool operator==(const Piece& o) const { return colour == o.colour && whole == o.whole && text == o.text; }
};
using Line = std::vector<Piece>;

float textWidth(const std::string& text);
float lineWidth(const Line& line);
// Appends text to the line's last piece when it has the same colour.
void append(Line& line, const std::string& text, ImU32 colour);

// A line broken at spaces into lines no wider than `width`, each piece
// keeping its colour; a word wider than the whole width has a line to itself.
std::vector<Line> wrapLine(const Line& line, float width);

// The line with " ..." at its end (in `colour` when nothing of it is left),
// less as many words as it takes to fit `width`.
Line shortened(Line line, float width, ImU32 colour);

// A bar's lines wrapped to its width and cut to the lines it holds (the
// last ending in "..."), laid out again only when the lines, the width or
// the lines held change.
class WrappedText {
 public:
  const std::vector<Line>& layout(const std::vector<Line>& lines, float width, std::size_t holds, ImU32 moreColour);
  bool shortened() const { return shortened_; }
  long long layouts() const { return layouts_; }  // how many times it laid its text out

 private:
  std::vector<Line> lines_, wrapped_;
  float width_ = -1.0f;
  std::size_t holds_ = 0;
  bool shortened_ = false;
  long long layouts_ = 0;
};

}  // namespace demo
