#pragma once
// The scene's drawing on OpenGL 3.3 core (the desktop) or OpenGL ES 3.0
// (WebGL 2, the page), one backend for both: one shader program, vertices of
// a position and an rgba8 colour interleaved in one buffer, an orthographic
// matrix per pane. Points are round (the fragment shader keeps the disc of
// gl_PointCoord), lines are quads of their width in pixels; smooth ones get
// a soft edge one pixel wide.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "palette.h"
#include "view.h"

namespace demo {

// The shading language's version line that both the scene's shaders and Dear
// ImGui's OpenGL3 backend compile with.
#ifdef __EMSCRIPTEN__
constexpr const char* glslVersion = "#version 300 es";
#else
constexpr const char* glslVersion = "#version 330 core";
#endif

// Vertices in world units, each with its colour: triangles by threes, lines
// by pairs, points one each.
struct ShapeBatch {
  std::vector<float> xy;
  std::vector<unsigned char> rgba;
  void clear() { xy.clear(); rgba.clear(); }
  bool empty() const { return xy.empty(); }
  std::size_t vertices() const { return xy.size() / 2; }
  void add(const Eigen::Vector2d& p, Rgb c, unsigned char alpha = 255) {
    xy.push_back(static_cast<float>(p.x()));
    xy.push_back(static_cast<float>(p.y()));
    rgba.insert(rgba.end(), {c.r, c.g, c.b, alpha});
  }
  void line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Rgb c, unsigned char alpha = 255) {
    add(a, c, alpha);
    add(b, c, alpha);
  }
};

class Painter {
 public:
  Painter() = default;
  Painter(const Painter&) = delete;
  Painter& operator=(const Painter&) = delete;
  ~Painter();  // frees the GL objects (the context must still be current)

  // Clears the whole window (the colour shows between panes).
  void clearWindow(int width, int height, Rgb colour);
  // Fills a rectangle of the window (pixels, origin top-left) with a colour
  // by a scissored clear: a software rasteriser fills it without shading or
  // blending a fragment, which the same rectangle drawn as triangles costs.
  void clearRect(const PixelRect& rect, int windowHeight, Rgb colour);
  // Maps the pane's world rectangle onto its pixels (GL's window origin is
  // bottom-left, the pane's top-left) and keeps the drawing inside it until
  // endPane; clears it to `background` when given.
  void beginPane(const ViewTransform& view, int windowHeight, const Rgb* background = nullptr);
  void endPane();

  void triangles(const ShapeBatch& batch);
  void lines(const ShapeBatch& batch, double widthPixels, bool smooth);
  void points(const ShapeBatch& batch, double diameterPixels, bool smooth);

 private:
  // One vertex as the shader reads it: world position, the signed distance
  // in pixels across a line (0 elsewhere), colour.
  struct Vertex {
    float x, y, across;
    std::uint8_t rgba[4];
  };
  enum class Kind { Fill = 0, Line = 1, Point = 2 };
  void ensureProgram();
  // Uploads vertices_ and draws them; edge and feather are the shader's
  // uniforms (pixels): a line's half width with its soft edge, a point's size.
  void draw(unsigned mode, Kind kind, float edge, float feather);

  unsigned program_ = 0, vertexArray_ = 0, buffer_ = 0;
  int kindLocation_ = -1, edgeLocation_ = -1, featherLocation_ = -1, matrixLocation_ = -1;
  float largestPoint_ = 1.0f;  // GL_ALIASED_POINT_SIZE_RANGE's upper end
  double pixelsPerUnit_ = 1.0;
  std::vector<Vertex> vertices_;
};

}  // namespace demo
