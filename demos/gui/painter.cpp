#include "painter.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "gl_api.h"

namespace demo {

namespace {
// After glslVersion's line; ES needs a float precision (pixel distances
// up to a few thousand want more than mediump's 11 bits).
constexpr const char* glslPrecision = "\nprecision highp float;\n";

// The orthographic matrix (glOrtho's, near −1 and far 1) as the shader's
// u_matrix: the pane's world rectangle onto normalised device coordinates.
constexpr const char* vertexShader = R"(
uniform mat4 u_matrix;
uniform float u_edge;
layout(location = 0) in vec2 a_position;
layout(location = 1) in float a_across;
layout(location = 2) in vec4 a_colour;
out vec4 v_colour;
out float v_across;
void main() {
  gl_Position = u_matrix * vec4(a_position, 0.0, 1.0);
  gl_PointSize = 2.0 * u_edge;
  v_colour = a_colour;
  v_across = a_across;
}
)";

// Coverage of a line at distance d from its axis, with half width w/2 and a
// soft edge of f pixels (u_edge = w/2 + f/2): clamp((u_edge − |d|) / f, 0, 1),
// 1 across the whole quad when f = 0. A point is the same disc, d its
// distance in pixels from the centre of its square (gl_PointCoord ∈ [0, 1]²).
constexpr const char* fragmentShader = R"(
uniform int u_kind;
uniform float u_edge;
uniform float u_feather;
in vec4 v_colour;
in float v_across;
out vec4 o_colour;
void main() {
  float d = 0.0;
  if (u_kind == 1) d = abs(v_across);
  else if (u_kind == 2) d = length(gl_PointCoord - vec2(0.5)) * 2.0 * u_edge;
  float coverage = 1.0;
  if (u_kind != 0) {
    if (u_feather > 0.0) coverage = clamp((u_edge - d) / u_feather, 0.0, 1.0);
    else if (d > u_edge) discard;
  }
  if (coverage <= 0.0) discard;
  o_colour = vec4(v_colour.rgb, v_colour.a * coverage);
}
)";

unsigned compile(unsigned type, const char* body) {
  const unsigned shader = glCreateShader(type);
  const char* parts[] = {glslVersion, glslPrecision, body};
  glShaderSource(shader, 3, parts, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok) return shader;
  char log[1024] = "";
  glGetShaderInfoLog(shader, sizeof log, nullptr, log);
  glDeleteShader(shader);
  throw std::runtime_error(std::string("the scene's shader does not compile: ") + log);
}

constexpr float featherPixels = 1.0f;  // the soft edge of smooth lines and points
}  // namespace

Painter::~Painter() {
  if (!program_) return;
  glDeleteBuffers(1, &buffer_);
  glDeleteVertexArrays(1, &vertexArray_);
  glDeleteProgram(program_);
}

void Painter::ensureProgram() {
  if (program_) return;
  const unsigned vertex = compile(GL_VERTEX_SHADER, vertexShader);
  const unsigned fragment = compile(GL_FRAGMENT_SHADER, fragmentShader);
  program_ = glCreateProgram();
  glAttachShader(program_, vertex);
  glAttachShader(program_, fragment);
  glLinkProgram(program_);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint ok = 0;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[1024] = "";
    glGetProgramInfoLog(program_, sizeof log, nullptr, log);
    glDeleteProgram(program_);
    program_ = 0;
    throw std::runtime_error(std::string("the scene's shaders do not link: ") + log);
  }
  kindLocation_ = glGetUniformLocation(program_, "u_kind");
  edgeLocation_ = glGetUniformLocation(program_, "u_edge");
  featherLocation_ = glGetUniformLocation(program_, "u_feather");
  matrixLocation_ = glGetUniformLocation(program_, "u_matrix");

  glGenVertexArrays(1, &vertexArray_);
  glGenBuffers(1, &buffer_);
  glBindVertexArray(vertexArray_);
  glBindBuffer(GL_ARRAY_BUFFER, buffer_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<void*>(offsetof(Vertex, x)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<void*>(offsetof(Vertex, across)));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(Vertex), reinterpret_cast<void*>(offsetof(Vertex, rgba)));
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);

  GLfloat range[2] = {1.0f, 1.0f};
  glGetFloatv(GL_ALIASED_POINT_SIZE_RANGE, range);
  largestPoint_ = range[1];
}

void Painter::clearWindow(int width, int height, Rgb colour) {
  glViewport(0, 0, width, height);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(colour.r / 255.f, colour.g / 255.f, colour.b / 255.f, 1.f);
  glClear(GL_COLOR_BUFFER_BIT);
}

void Painter::clearRect(const PixelRect& r, int windowHeight, Rgb colour) {
  glEnable(GL_SCISSOR_TEST);
  glScissor(r.x, windowHeight - r.y - r.height, r.width, r.height);
  glClearColor(colour.r / 255.f, colour.g / 255.f, colour.b / 255.f, 1.f);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
}

void Painter::beginPane(const ViewTransform& view, int windowHeight, const Rgb* background) {
  ensureProgram();
  const PixelRect& p = view.pane;
  glViewport(p.x, windowHeight - p.y - p.height, p.width, p.height);
  glScissor(p.x, windowHeight - p.y - p.height, p.width, p.height);
  glEnable(GL_SCISSOR_TEST);
  if (background) {
    glClearColor(background->r / 255.f, background->g / 255.f, background->b / 255.f, 1.f);
    glClear(GL_COLOR_BUFFER_BIT);
  }
  // Colour blends over what is drawn; the window's alpha stays 1 (a page
  // composites its canvas with what lies under it).
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
#ifndef __EMSCRIPTEN__
  glEnable(GL_PROGRAM_POINT_SIZE);  // gl_PointSize (always on in ES)
#endif
  pixelsPerUnit_ = view.pixelsPerUnit;
  const Eigen::Vector2d lo = view.worldMin, hi = view.worldMax;
  // glOrtho(l, r, b, t, −1, 1), column-major.
  const float matrix[16] = {static_cast<float>(2.0 / (hi.x() - lo.x())), 0, 0, 0,
                            0, static_cast<float>(2.0 / (hi.y() - lo.y())), 0, 0,
                            0, 0, -1, 0,
                            static_cast<float>(-(hi.x() + lo.x()) / (hi.x() - lo.x())),
                            static_cast<float>(-(hi.y() + lo.y()) / (hi.y() - lo.y())), 0, 1};
  glUseProgram(program_);
  glUniformMatrix4fv(matrixLocation_, 1, GL_FALSE, matrix);
  glBindVertexArray(vertexArray_);
  glBindBuffer(GL_ARRAY_BUFFER, buffer_);
}

void Painter::endPane() {
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glUseProgram(0);
  glDisable(GL_SCISSOR_TEST);
}

void Painter::draw(unsigned mode, Kind kind, float edge, float feather) {
  if (vertices_.empty()) return;
  glUniform1i(kindLocation_, static_cast<int>(kind));
  glUniform1f(edgeLocation_, edge);
  glUniform1f(featherLocation_, feather);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices_.size() * sizeof(Vertex)), vertices_.data(),
               GL_STREAM_DRAW);
  glDrawArrays(mode, 0, static_cast<GLsizei>(vertices_.size()));
}

void Painter::triangles(const ShapeBatch& batch) {
  vertices_.clear();
  for (std::size_t k = 0; k < batch.vertices(); ++k)
    vertices_.push_back({batch.xy[2 * k], batch.xy[2 * k + 1], 0.f,
                         {batch.rgba[4 * k], batch.rgba[4 * k + 1], batch.rgba[4 * k + 2], batch.rgba[4 * k + 3]}});
  draw(GL_TRIANGLES, Kind::Fill, 0.f, 0.f);
}

// Each segment a→b as a quad: the axis ± (w/2 + f/2) pixels along its unit
// normal, in two triangles; `across` runs from −edge to +edge over it.
void Painter::lines(const ShapeBatch& batch, double widthPixels, bool smooth) {
  const float feather = smooth ? featherPixels : 0.f;
  const float edge = static_cast<float>(0.5 * widthPixels) + 0.5f * feather;
  const double offset = edge / pixelsPerUnit_;
  vertices_.clear();
  for (std::size_t k = 0; k + 1 < batch.vertices(); k += 2) {
    const Eigen::Vector2d a(batch.xy[2 * k], batch.xy[2 * k + 1]), b(batch.xy[2 * k + 2], batch.xy[2 * k + 3]);
    const Eigen::Vector2d d = b - a;
    const double length = d.norm();
    if (!(length > 0.0) || !std::isfinite(length)) continue;
    const Eigen::Vector2d n = Eigen::Vector2d(-d.y(), d.x()) * (offset / length);
    const std::uint8_t* ca = &batch.rgba[4 * k];
    const std::uint8_t* cb = &batch.rgba[4 * k + 4];
    auto corner = [&](const Eigen::Vector2d& p, float side, const std::uint8_t* c) {
      vertices_.push_back({static_cast<float>(p.x()), static_cast<float>(p.y()), side * edge, {c[0], c[1], c[2], c[3]}});
    };
    corner(a + n, 1.f, ca), corner(a - n, -1.f, ca), corner(b + n, 1.f, cb);
    corner(b + n, 1.f, cb), corner(a - n, -1.f, ca), corner(b - n, -1.f, cb);
  }
  draw(GL_TRIANGLES, Kind::Line, edge, feather);
}

// A point is at most the GL's largest point size (llvmpipe: 255 px), as GL
// points always were here: a collision disc zoomed past it is drawn that size
// rather than filling the pane once per particle.
void Painter::points(const ShapeBatch& batch, double diameterPixels, bool smooth) {
  const float feather = smooth ? featherPixels : 0.f;
  const float size = std::min(static_cast<float>(diameterPixels) + feather, largestPoint_);
  vertices_.clear();
  for (std::size_t k = 0; k < batch.vertices(); ++k)
    vertices_.push_back({batch.xy[2 * k], batch.xy[2 * k + 1], 0.f,
                         {batch.rgba[4 * k], batch.rgba[4 * k + 1], batch.rgba[4 * k + 2], batch.rgba[4 * k + 3]}});
  // u_edge is half the point's square; the disc's soft edge ends at its side.
  draw(GL_POINTS, Kind::Point, 0.5f * size, feather);
}

}  // namespace demo
