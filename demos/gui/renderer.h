#pragma once
// Draws a simulation into a pane: a handful of draw calls per pane (walls,
// lines by width, points by size), whatever the number of particles, through
// the shader backend of painter.h.
#include <map>
#include <vector>

#include "exact_motion.h"
#include "painter.h"
#include "palette.h"
#include "particles/constraint_solver.h"
#include "simulation.h"
#include "view.h"

namespace demo {

struct DrawOptions {
  bool forces = false;      // arrows per force type ('f')
  bool constraints = true;  // wires, rods, lines ('c'): drawing only, they always act
  bool ghost = true;        // the exact motion beside the simulation, where a scene has one ('g')
  // Simulated seconds a frame advances while running (0: paused or
  // lockstep): with a dt longer than this, the drawing is interpolated.
  double frameTime = 0.0;
};

// Diameter in pixels of a point particle: at least minParticlePixels so that
// every particle can be seen and grabbed, larger in a small scene, and no more
// than the typical spacing so that a dense cloth still shows its mesh.
constexpr int minParticlePixels = 6;
int pointDiameter(const particles::Phase& phase, double pixelsPerUnit);
// The typical distance in pixels between neighbouring particles: the side of
// the square each would have if they tiled their bounding box; 0 for fewer
// than two finite particles.
double particleSpacingPixels(const particles::Phase& phase, double pixelsPerUnit);

// A surface (a scene with faces, the cloth) is drawn in the detail its
// spacing on screen allows: its springs from meshLinePixels up, its free
// particles from meshDotPixels up. Finer, they would fill the surface with a
// solid block of lines or dots (and cost a software rasteriser a primitive
// each); the shaded faces alone then show it, with its pinned and grabbed
// particles. Zooming in brings the mesh back.
constexpr double meshLinePixels = 6.0;
constexpr double meshDotPixels = 2.0 * minParticlePixels;

class Renderer {
 public:
  // Clears the whole window (the colour shows between panes).
  void clearWindow(int width, int height, Rgb colour);
  // Fills a rectangle of the window with a colour (Painter::clearRect).
  void clearRect(const PixelRect& rect, int windowHeight, Rgb colour);
  // ghost: the exact solution at the pane's time, or null.
  void drawPane(const Simulation& simulation, const ViewTransform& view, int windowHeight,
                const DrawOptions& options, const GhostFrame* ghost = nullptr);

  // What the last drawPane drew. Its shaded faces: how many, how many it
  // left unshaded (a mesh stretched past the fill budget, as a diverged cloth
  // is), and the pixels they cover (each clipped to the pane's area) against
  // the pane's; the surface's detail: its spacing on screen, and whether its
  // springs and free particles were drawn (both true in a scene without
  // faces); and where between the last two steps its positions were
  // (Simulation::drawnFraction; 1: the state).
  struct PaneDrawing {
    int shaded = 0, leftOut = 0;
    double shadedPixels = 0.0, panePixels = 0.0;
    double spacingPixels = 0.0;
    bool springsDrawn = true, particlesDrawn = true;
    double drawnFraction = 1.0;
  };
  const PaneDrawing& drawing() const { return drawing_; }

  // The backend, for marks drawn over a pane (build mode's).
  Painter& painter() { return painter_; }

 private:
  using Batch = ShapeBatch;

  // drawPane's phases: collect the batches, then draw them back to front
  // into the cleared pane (smooth: antialiased).
  void collectPane(const Simulation& simulation, const ViewTransform& view, const DrawOptions& options,
                   const GhostFrame* ghost);
  bool smoothPane() const;
  void drawBatches(bool smooth);
  void collectWalls(const particles::ParticleSystem& system, const ViewTransform& view);  // colliders
  void collectFaces(const Simulation& simulation, const ViewTransform& view);
  // surface: the springs are drawn faintly over the shaded faces.
  // The loads at the current state: each force type's Q (forceByType_, in
  // the order of loadTypes_) and, with constraints, Jᵀλ by the renderer's own
  // solve as one more type, and each constraint's force (|λ| times its
  // largest gradient block) in constraintForce_.
  void collectLoads(const particles::ParticleSystem& system);
  void collectConstraintForces(const particles::ParticleSystem& system);
  // Springs in their strain's colour; on a surface, faintly over the faces.
  void collectSprings(const particles::ParticleSystem& system, double pixelsPerUnit, bool surface);
  // Wires, rods and lines in the colour of the force they carry.
  void collectConstraints(const particles::ParticleSystem& system);
  void collectForceArrows(const particles::ParticleSystem& system, const ViewTransform& view);
  void collectParticles(const Simulation& simulation, const ViewTransform& view);
  void collectGhost(const GhostFrame& ghost, const ViewTransform& view, int diameter);
  // A spring as a coil of zigzags (a few springs) or a straight line (a mesh).
  void addSpring(Batch& batch, const Eigen::Vector2d& a, const Eigen::Vector2d& b, Rgb colour, unsigned char alpha,
                 bool coil, double pixelsPerUnit);
  void addCircle(Batch& batch, const Eigen::Vector2d& centre, double radius, Rgb colour);
  Painter painter_;
  Batch walls_, wallOutlines_, faces_, springs_, constraints_, arrows_, ghostLines_;
  std::map<int, Batch> pointsBySize_;  // diameter in pixels → particles
  std::map<int, Batch> discsBySize_;   // collision discs of collidable particles, translucent
  Batch ghostPoints_;
  int ghostDiameter_ = minParticlePixels;
  PaneDrawing drawing_;
  particles::Sketch sketch_;
  std::vector<Eigen::VectorXd> forceByType_;
  Eigen::VectorXd totalForce_;
  // The positions drawn (drawPane's phase): the state's, or drawnX_ between
  // the last two steps (Simulation::drawnFraction).
  particles::Phase phaseOf(const particles::ParticleSystem& system) const {
    return system.phase(*drawn_, system.velocities());
  }
  const Eigen::VectorXd* drawn_ = nullptr;
  Eigen::VectorXd drawnX_;
  std::vector<const char*> loadTypes_;  // Force::type() of each forceByType_ entry, then "constraint"
  std::vector<double> constraintForce_;
  std::vector<Eigen::Vector2d> gradient_, gradientRate_;
  particles::ConstraintSolver arrowSolver_;  // its own λ, so drawing never disturbs the run
};

}  // namespace demo
