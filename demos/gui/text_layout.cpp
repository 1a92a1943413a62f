#include "text_layout.h"

namespace demo {

float textWidth(const std::string& text) { return ImGui::CalcTextSize(text.c_str()).x; }

namespace {
// Calls f(token) for each token of a piece as wrapLine takes them: the
// spaces before a word and the word (a whole piece is one token).
template <class F>
void forEachToken(const Piece& piece, F&& f) {
  const std::string& t = piece.text;
  std::size_t start = 0;
  while (start < t.size()) {
    const std::size_t word = t.find_first_not_of(' ', start);
    if (word == std::string::npos) break;  // trailing spaces end a piece
    std::size_t end = piece.whole ? t.size() : t.find(' ', word);
    if (end == std::string::npos) end = t.size();
    f(start, word, end);
    start = end;
  }
}
}  // namespace

// Measured token by token, as wrapLine measures (ImGui rounds each
// measurement up to a whole pixel, so the sum over tokens is what fits).
float lineWidth(const Line& line) {
  float width = 0.0f;
  for (const Piece& piece : line)
    forEachToken(piece, [&](std::size_t start, std::size_t, std::size_t end) {
      width += textWidth(piece.text.substr(start, end - start));
    });
  return width;
}

void append(Line& line, const std::string& text, ImU32 colour) {
  if (!line.empty() && line.back().colour == colour) line.back().text += text;
  else line.push_back({text, colour});
}

std::vector<Line> wrapLine(const Line& line, float width) {
  std::vector<Line> lines(1);
  float x = 0.0f;
  for (const Piece& piece : line)
    forEachToken(piece, [&](std::size_t start, std::size_t word, std::size_t end) {
      std::string token = piece.text.substr(start, end - start);  // the spaces before the word, then the word
      if (x > 0.0f && x + textWidth(token) > width) {
        lines.emplace_back();
        token = piece.text.substr(word, end - word);
        x = 0.0f;
      }
      append(lines.back(), token, piece.colour);
      x += textWidth(token);
    });
  return lines;
}

Line shortened(Line line, float width, ImU32 colour) {
  const std::string more = " ...";
  while (!line.empty() && lineWidth(line) + textWidth(more) > width) {
    std::string& last = line.back().text;
    const std::size_t space = last.find_last_of(' ');
    if (space == std::string::npos || last.find_first_not_of(' ') == std::string::npos) line.pop_back();
    else last.erase(space);
  }
  append(line, more, line.empty() ? colour : line.back().colour);
  return line;
}

const std::vector<Line>& WrappedText::layout(const std::vector<Line>& lines, float width, std::size_t holds,
                                             ImU32 moreColour) {
  if (width == width_ && holds == holds_ && lines == lines_) return wrapped_;
  ++layouts_;
  lines_ = lines;
  width_ = width;
  holds_ = holds;
  wrapped_.clear();
  for (const Line& line : lines)
    for (Line& part : wrapLine(line, width)) wrapped_.push_back(std::move(part));
  shortened_ = wrapped_.size() > holds;
  if (shortened_) {
    wrapped_.resize(holds);
    wrapped_.back() = demo::shortened(wrapped_.back(), width, moreColour);
  }
  return wrapped_;
}

}  // namespace demo
