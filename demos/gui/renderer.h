#pragma once
// Draws a simulation into a pane with OpenGL vertex arrays: a handful of draw
// calls per pane (walls, lines by width, points by size), whatever the
// number of particles.
#include <map>
#include <vector>

#include "exact_motion.h"
#include "palette.h"
#include "particles/constraint_solver.h"
#include "simulation.h"
#include "view.h"

namespace demo {

struct DrawOptions {
  bool forces = false;      // arrows per force type ('f')
  bool constraints = true;  // wires, rods, lines ('c'): drawing only, they always act
  bool ghost = true;        // the exact motion beside the simulation, where a scene has one ('g')
};

// Diameter in pixels of a point particle: at least minParticlePixels so that
// every particle can be seen and grabbed, larger in a small scene, and no more
// than the typical spacing so that a dense cloth still shows its mesh.
constexpr int minParticlePixels = 6;
int pointDiameter(const particles::ParticleSystem& system, double pixelsPerUnit);

class Renderer {
 public:
  // Clears the whole window (the colour shows between panes).
  void clearWindow(int width, int height, Rgb colour);
  // ghost: the exact solution at the pane's time, or null.
  void drawPane(const Simulation& simulation, const ViewTransform& view, int windowHeight,
                const DrawOptions& options, const GhostFrame* ghost = nullptr);

  // The last drawPane's shaded faces: how many, how many it left unshaded (a
  // mesh stretched past the fill budget, as a diverged cloth is), and the
  // pixels they cover (each clipped to the pane's area) against the pane's.
  struct FaceFill {
    int shaded = 0, leftOut = 0;
    double shadedPixels = 0.0, panePixels = 0.0;
  };
  const FaceFill& faceFill() const { return faceFill_; }

 private:
  // Vertices of one primitive kind: 2 floats and 4 bytes of colour each.
  struct Batch {
    std::vector<float> xy;
    std::vector<unsigned char> rgba;
    void clear() { xy.clear(); rgba.clear(); }
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

  // drawPane's phases: collect the batches, set up the pane's GL state (true:
  // antialiased), draw the batches back to front, restore the state.
  void collectPane(const Simulation& simulation, const ViewTransform& view, const DrawOptions& options,
                   const GhostFrame* ghost);
  bool beginPane(const ViewTransform& view, int windowHeight) const;
  void drawBatches(bool smooth) const;
  static void endPane();
  void collectWalls(const particles::ParticleSystem& system, const ViewTransform& view);  // colliders
  void collectFaces(const Simulation& simulation, const ViewTransform& view);
  // surface: the springs are drawn faintly over the shaded faces.
  void collectSketches(const particles::ParticleSystem& system, const DrawOptions& options, double pixelsPerUnit,
                       bool surface);
  void collectForceArrows(const particles::ParticleSystem& system, const ViewTransform& view);
  void collectParticles(const Simulation& simulation, const ViewTransform& view);
  void collectGhost(const GhostFrame& ghost, const ViewTransform& view, int diameter);
  // A spring as a coil of zigzags (a few springs) or a straight line (a mesh).
  void addSpring(Batch& batch, const Eigen::Vector2d& a, const Eigen::Vector2d& b, Rgb colour, unsigned char alpha,
                 bool coil, double pixelsPerUnit);
  void addCircle(Batch& batch, const Eigen::Vector2d& centre, double radius, Rgb colour);
  static void draw(const Batch& batch, unsigned mode);
  Batch walls_, faces_, springs_, constraints_, arrows_, ghostLines_;
  std::map<int, Batch> pointsBySize_;  // diameter in pixels → particles
  std::map<int, Batch> discsBySize_;   // collision discs of collidable particles, translucent
  Batch ghostPoints_;
  int ghostDiameter_ = minParticlePixels;
  FaceFill faceFill_;
  particles::Sketch sketch_;
  std::vector<Eigen::VectorXd> forceByType_;
  Eigen::VectorXd totalForce_;
  particles::ConstraintSolver arrowSolver_;  // its own λ, so drawing never disturbs the run
};

}  // namespace demo
