#include "renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "particles/constants.h"
#include "particles/constraints/circular_wire.h"
#include "particles/forces/spring.h"

namespace demo {

namespace {
constexpr double arrowReferencePixels = 28.0;  // length of a typical (90th percentile) arrow
constexpr double arrowMaxPixels = 90.0;
constexpr double arrowMinPixels = 2.0;
constexpr int circleSegments = 96;
constexpr std::size_t smoothLineLimit = 8000;  // lines drawn antialiased up to this many
// Shaded faces fill at most this many times the pane's area. A cloth that
// holds together covers each pixel about once, so it is always drawn whole;
// one torn apart by a diverging integrator (faces thousands of panes wide,
// each filled by a software rasteriser) is drawn up to the budget, and the
// frame stays interactive.
constexpr double faceFillBudget = 4.0;
constexpr int coilSpringLimit = 16;            // scenes with at most this many springs draw them as coils
constexpr int coilTurns = 8;
constexpr double coilWidthPixels = 7.0;

// A pixel size from a double that may be NaN or huge (a diverged state): an
// int in [lo, hi] without undefined behaviour.
int pixels(double value, int lo, int hi) {
  if (!(value >= lo)) return lo;
  if (!(value <= hi)) return hi;
  return static_cast<int>(std::lround(value));
}
}  // namespace

double particleSpacingPixels(const particles::Phase& phase, double pixelsPerUnit) {
  Eigen::Vector2d lo, hi;
  int finite = 0;
  for (int i = 0; i < phase.size(); ++i) {
    const Eigen::Vector2d x = phase.position(i);
    if (!x.allFinite()) continue;
    lo = finite ? lo.cwiseMin(x) : x;
    hi = finite ? hi.cwiseMax(x) : x;
    ++finite;
  }
  if (finite < 2) return 0.0;
  const Eigen::Vector2d extent = (hi - lo) * pixelsPerUnit;
  return std::sqrt(std::max(extent.x(), 1.0) * std::max(extent.y(), 1.0) / finite);
}

int pointDiameter(const particles::Phase& phase, double pixelsPerUnit) {
  const double byScale = std::clamp(0.022 * pixelsPerUnit, 8.0, 12.0);
  const double spacing = particleSpacingPixels(phase, pixelsPerUnit);
  if (spacing == 0.0) return pixels(byScale, minParticlePixels, 12);
  return pixels(std::min(0.45 * spacing, byScale), minParticlePixels, 12);
}

void Renderer::clearWindow(int width, int height, Rgb colour) { painter_.clearWindow(width, height, colour); }

void Renderer::clearRect(const PixelRect& rect, int windowHeight, Rgb colour) {
  painter_.clearRect(rect, windowHeight, colour);
}

void Renderer::drawPane(const Simulation& simulation, const ViewTransform& view, int windowHeight,
                        const DrawOptions& options, const GhostFrame* ghost) {
  collectPane(simulation, view, options, ghost);
  painter_.beginPane(view, windowHeight, &palette::background);
  drawBatches(smoothPane());
  painter_.endPane();
}

void Renderer::collectPane(const Simulation& simulation, const ViewTransform& view, const DrawOptions& options,
                           const GhostFrame* ghost) {
  const particles::ParticleSystem& system = simulation.system();
  for (Batch* b : {&walls_, &wallOutlines_, &faces_, &springs_, &constraints_, &arrows_, &ghostLines_, &ghostPoints_}) b->clear();
  for (auto& entry : pointsBySize_) entry.second.clear();
  for (auto& entry : discsBySize_) entry.second.clear();

  const double fraction = simulation.drawnFraction(options.frameTime);
  if (fraction < 1.0) {
    const Eigen::VectorXd& before = simulation.previousPositions();
    drawnX_ = before + fraction * (system.positions() - before);
    drawn_ = &drawnX_;
  } else {
    drawn_ = &system.positions();
  }
  const particles::Phase phase = phaseOf(system);
  const bool surface = !simulation.scene().faces.empty();
  drawing_ = {};
  drawing_.drawnFraction = fraction;
  drawing_.spacingPixels = particleSpacingPixels(phase, view.pixelsPerUnit);
  drawing_.springsDrawn = !surface || drawing_.spacingPixels >= meshLinePixels;
  drawing_.particlesDrawn = !surface || drawing_.spacingPixels >= meshDotPixels;

  collectWalls(system, view);
  collectFaces(simulation, view);
  const bool constraints = options.constraints && !system.constraints().empty();
  if (options.forces || constraints) collectLoads(system);
  if (drawing_.springsDrawn) collectSprings(system, view.pixelsPerUnit, surface);
  if (constraints) collectConstraints(system);
  if (options.forces) collectForceArrows(system, view);
  collectParticles(simulation, view);
  if (ghost && options.ghost) collectGhost(*ghost, view, pointDiameter(phase, view.pixelsPerUnit));
}

// Antialiasing costs a software rasteriser (llvmpipe, Xvfb; SwiftShader in a
// browser) a pixel more of every line; large scenes draw crisp instead so
// that they stay interactive there.
bool Renderer::smoothPane() const { return springs_.xy.size() + arrows_.xy.size() < 2 * smoothLineLimit; }

void Renderer::drawBatches(bool smooth) {
  painter_.triangles(faces_);
  painter_.triangles(walls_);
  painter_.lines(wallOutlines_, 1.5, smooth);
  for (const auto& [diameter, batch] : discsBySize_) painter_.points(batch, diameter, smooth);
  painter_.lines(ghostLines_, 1.5, smooth);
  painter_.points(ghostPoints_, ghostDiameter_, smooth);
  painter_.lines(springs_, smooth ? 1.4 : 1.0, smooth);
  painter_.lines(constraints_, 2.0, smooth);
  painter_.lines(arrows_, 1.6, smooth);
  for (const auto& [diameter, batch] : pointsBySize_) painter_.points(batch, diameter, smooth);
}

// The outline of a collider grown by its radius, counter-clockwise: the
// vertices joined by arcs of radius r about each (for a capsule the two ends,
// for a disc one whole circle); a half-plane is cut to a square of side 2·far.
static std::vector<Eigen::Vector2d> colliderOutline(const particles::Collider& c, double far) {
  if (c.shape == particles::ColliderShape::HalfPlane) {
    const Eigen::Vector2d p = c.points[0], n = c.normal, t(-n.y(), n.x());
    return {p - far * t, p - far * t - 2.0 * far * n, p + far * t - 2.0 * far * n, p + far * t};
  }
  if (c.radius == 0.0) return c.points;
  const std::size_t count = c.points.size();
  std::vector<Eigen::Vector2d> outline;
  for (std::size_t k = 0; k < count; ++k) {
    const Eigen::Vector2d& p = c.points[k];
    double from = 0.0, to = 2.0 * particles::kPi;
    if (count > 1) {
      const Eigen::Vector2d in = p - c.points[(k + count - 1) % count], out = c.points[(k + 1) % count] - p;
      from = std::atan2(-in.x(), in.y());  // outward normal (e.y, −e.x) of the edge arriving
      to = std::atan2(-out.x(), out.y());   // and of the edge leaving
      while (to < from) to += 2.0 * particles::kPi;
    }
    const int segments = std::max(1, static_cast<int>(std::ceil((to - from) / (2.0 * particles::kPi) * circleSegments)));
    for (int s = 0; s <= segments; ++s) {
      const double angle = from + (to - from) * s / segments;
      outline.push_back(p + c.radius * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
    }
  }
  return outline;
}

void Renderer::collectWalls(const particles::ParticleSystem& system, const ViewTransform& view) {
  const double far = 4.0 * (view.worldMax - view.worldMin).norm() + view.worldMin.norm() + view.worldMax.norm();
  for (const particles::Collider& c : system.colliders()) {
    const std::vector<Eigen::Vector2d> outline = colliderOutline(c, far);
    for (std::size_t k = 1; k + 1 < outline.size(); ++k)  // a fan: the outline is convex
      for (const Eigen::Vector2d& v : {outline[0], outline[k], outline[k + 1]}) walls_.add(v, palette::wall);
    for (std::size_t k = 0; k < outline.size(); ++k)
      wallOutlines_.line(outline[k], outline[(k + 1) % outline.size()], palette::wallOutline);
  }
}

// A surface drawn as shaded quads in the stress colour map: a face turns
// orange where it is stretched beyond its rest area and cyan where it is
// compressed (palette::strainColour); a face
// turned over (a fold, negative signed area) shows the back colour; a face
// with a torn side is not drawn.
void Renderer::collectFaces(const Simulation& simulation, const ViewTransform& view) {
  const particles::Phase phase = phaseOf(simulation.system());
  const auto& faces = simulation.scene().faces;
  const auto& rest = simulation.restFaceAreas();
  const std::vector<char>& intact = simulation.intactFaces();  // a face with a torn side is a hole
  const double paneArea = static_cast<double>(view.pane.width) * view.pane.height;
  const double pixelArea = view.pixelsPerUnit * view.pixelsPerUnit;
  double filled = 0.0;  // pixels, each face's clipped to the pane's area
  drawing_.panePixels = paneArea;
  for (std::size_t k = 0; k < faces.size() && k < rest.size(); ++k) {
    if (!intact[k]) continue;
    const auto& f = faces[k];
    const double area = faceArea(phase, f);
    if (!std::isfinite(area) || !(std::abs(rest[k]) > 0.0)) continue;
    const double pixels = std::min(std::abs(area) * pixelArea, paneArea);
    filled += pixels;
    if (filled > faceFillBudget * paneArea) {
      ++drawing_.leftOut;
      continue;
    }
    ++drawing_.shaded;
    drawing_.shadedPixels += pixels;
    const double ratio = area / rest[k];
    // Its strain as a length's: √(area / rest area) − 1, so a face and a
    // spring stretched alike show alike.
    const Rgb c = palette::strainColour(ratio >= 0.0 ? palette::clothFront : palette::clothBack,
                                        std::sqrt(std::abs(ratio)) - 1.0);
    for (int corner : {0, 1, 2, 0, 2, 3}) faces_.add(phase.position(f[corner]), c);
  }
}

void Renderer::collectSprings(const particles::ParticleSystem& system, double pixelsPerUnit, bool surface) {
  const particles::Phase phase = phaseOf(system);
  int springs = 0;
  for (const auto& force : system.forceObjects())
    springs += dynamic_cast<const particles::SpringForce*>(force.get()) != nullptr;
  const bool coils = springs <= coilSpringLimit;
  for (const auto& force : system.forceObjects()) {
    sketch_.lines.clear();
    sketch_.circles.clear();
    force->sketch(phase, sketch_);
    const bool mouse = dynamic_cast<const particles::MouseSpringForce*>(force.get()) != nullptr;
    const auto* spring = dynamic_cast<const particles::SpringForce*>(force.get());
    const Rgb kind = sketchColour(force->type());
    for (const auto& l : sketch_.lines) {
      const double strain = spring && spring->restLength() > 0.0 ? (l.b - l.a).norm() / spring->restLength() - 1.0 : 0.0;
      addSpring(springs_, l.a, l.b, palette::strainColour(kind, strain), mouse ? 255 : surface ? 90 : 220,
                spring && coils, pixelsPerUnit);
    }
    for (const auto& c : sketch_.circles) addCircle(springs_, c.centre, c.radius, kind);
  }
}

void Renderer::collectConstraints(const particles::ParticleSystem& system) {
  const particles::Phase phase = phaseOf(system);
  double largest = 0.0;
  for (double f : constraintForce_)
    if (std::isfinite(f)) largest = std::max(largest, f);
  std::size_t k = 0;
  for (const auto& constraint : system.constraints()) {
    const double force = k < constraintForce_.size() ? constraintForce_[k] : 0.0;
    ++k;
    const Rgb colour = palette::constraintColour(sketchColour(constraint->type()), largest > 0.0 ? force / largest : 0.0);
    sketch_.lines.clear();
    sketch_.circles.clear();
    constraint->sketch(phase, sketch_);
    for (const auto& l : sketch_.lines) constraints_.line(l.a, l.b, colour);
    for (const auto& c : sketch_.circles) addCircle(constraints_, c.centre, c.radius, colour);
    // A bead on a circular wire is a pendulum: its rod to the centre, faintly.
    if (dynamic_cast<const particles::CircularWireConstraint*>(constraint.get()) && !sketch_.circles.empty())
      for (int i : constraint->particles()) constraints_.line(sketch_.circles.front().centre, phase.position(i), colour);
  }
}

void Renderer::addSpring(Batch& batch, const Eigen::Vector2d& a, const Eigen::Vector2d& b, Rgb colour,
                         unsigned char alpha, bool coil, double pixelsPerUnit) {
  const Eigen::Vector2d d = b - a;
  const double length = d.norm();
  if (!coil || !(length * pixelsPerUnit > 4.0 * coilTurns) || !std::isfinite(length)) {
    batch.line(a, b, colour, alpha);
    return;
  }
  // Straight leads of 10% at each end, then zigzags across the axis.
  const Eigen::Vector2d axis = d / length, side(-axis.y(), axis.x());
  const double width = coilWidthPixels / pixelsPerUnit;
  const int corners = 2 * coilTurns;
  Eigen::Vector2d previous = a + 0.1 * d;
  batch.line(a, previous, colour, alpha);
  for (int k = 1; k <= corners; ++k) {
    const double s = 0.1 + 0.8 * (k - 0.5) / corners;
    const Eigen::Vector2d corner = a + s * d + (k % 2 ? width : -width) * side;
    batch.line(previous, corner, colour, alpha);
    previous = corner;
  }
  batch.line(previous, a + 0.9 * d, colour, alpha);
  batch.line(a + 0.9 * d, b, colour, alpha);
}

void Renderer::collectGhost(const GhostFrame& ghost, const ViewTransform& view, int diameter) {
  for (const auto& [a, b] : ghost.springs) addSpring(ghostLines_, a, b, palette::ghost, 150, true, view.pixelsPerUnit);
  for (const auto& [a, b] : ghost.rods) ghostLines_.line(a, b, palette::ghost, 150);
  for (const Eigen::Vector2d& p : ghost.points) ghostPoints_.add(p, palette::ghost, 170);
  ghostDiameter_ = diameter + 2;
}

void Renderer::addCircle(Batch& batch, const Eigen::Vector2d& centre, double radius, Rgb colour) {
  for (int k = 0; k < circleSegments; ++k) {
    const double a0 = 2 * particles::kPi * k / circleSegments, a1 = 2 * particles::kPi * (k + 1) / circleSegments;
    batch.line(centre + radius * Eigen::Vector2d(std::cos(a0), std::sin(a0)),
               centre + radius * Eigen::Vector2d(std::cos(a1), std::sin(a1)), colour);
  }
}

void Renderer::collectLoads(const particles::ParticleSystem& system) {
  // Each force type's contribution Q_type at the current state, and the
  // constraint force Jᵀλ as the difference between (Q + Jᵀλ) and Q.
  const particles::Phase phase = phaseOf(system);
  const int n2 = 2 * system.size();
  loadTypes_.clear();
  for (const auto& force : system.forceObjects()) {
    auto it = std::find_if(loadTypes_.begin(), loadTypes_.end(),
                           [&](const char* t) { return std::strcmp(t, force->type()) == 0; });
    const std::size_t k = it - loadTypes_.begin();
    if (it == loadTypes_.end()) {
      loadTypes_.push_back(force->type());
      if (forceByType_.size() < loadTypes_.size()) forceByType_.emplace_back();
      forceByType_[k].setZero(n2);
    }
    force->apply(phase, forceByType_[k]);
  }
  totalForce_.setZero(n2);
  for (std::size_t k = 0; k < loadTypes_.size(); ++k) totalForce_ += forceByType_[k];
  constraintForce_.assign(system.constraints().size(), 0.0);
  if (system.constraints().empty()) return;
  const Eigen::VectorXd applied = totalForce_;
  collectConstraintForces(system);
  if (forceByType_.size() <= loadTypes_.size()) forceByType_.emplace_back();
  forceByType_[loadTypes_.size()] = totalForce_ - applied;
  loadTypes_.push_back("constraint");
}

void Renderer::collectConstraintForces(const particles::ParticleSystem& system) {
  const particles::Phase phase = phaseOf(system);
  arrowSolver_.settings = system.solver().settings;
  arrowSolver_.addConstraintForces(phase, system.constraints(), totalForce_);
  const Eigen::VectorXd& lambda = arrowSolver_.lambda();
  const auto& constraints = system.constraints();
  if (lambda.size() != static_cast<Eigen::Index>(constraints.size())) return;
  for (std::size_t k = 0; k < constraints.size(); ++k) {
    const std::size_t blocks = constraints[k]->particles().size();
    gradient_.assign(blocks, Eigen::Vector2d::Zero());
    gradientRate_.assign(blocks, Eigen::Vector2d::Zero());
    particles::ConstraintRow row;
    row.J = gradient_.data();
    row.Jdot = gradientRate_.data();
    constraints[k]->evaluate(phase, row);
    double largest = 0.0;
    for (const Eigen::Vector2d& g : gradient_) largest = std::max(largest, g.norm());
    constraintForce_[k] = std::abs(lambda[static_cast<Eigen::Index>(k)]) * largest;
  }
}

void Renderer::collectForceArrows(const particles::ParticleSystem& system, const ViewTransform& view) {
  const particles::Phase phase = phaseOf(system);
  const std::vector<const char*>& types = loadTypes_;
  std::vector<Rgb> colours;
  for (const char* type : types) colours.push_back(forceArrowColour(type));
  // One scale for every arrow in the pane: the 90th-percentile magnitude is
  // drawn arrowReferencePixels long, so both a gentle field and a hard pull show.
  std::vector<double> magnitudes;
  for (std::size_t k = 0; k < types.size(); ++k)
    for (int i = 0; i < system.size(); ++i) {
      const double m = forceByType_[k].segment<2>(2 * i).norm();
      if (m > 0.0 && std::isfinite(m)) magnitudes.push_back(m);
    }
  if (magnitudes.empty()) return;
  auto percentile = magnitudes.begin() + static_cast<long>(0.9 * (magnitudes.size() - 1));
  std::nth_element(magnitudes.begin(), percentile, magnitudes.end());
  const double pixelsPerForce = arrowReferencePixels / *percentile;

  for (std::size_t k = 0; k < types.size(); ++k)
    for (int i = 0; i < system.size(); ++i) {
      const Eigen::Vector2d f = forceByType_[k].segment<2>(2 * i);
      const double pixels = std::min(f.norm() * pixelsPerForce, arrowMaxPixels);
      if (!(pixels >= arrowMinPixels)) continue;
      const Eigen::Vector2d dir = f.normalized(), side(-dir.y(), dir.x());
      const Eigen::Vector2d from = phase.position(i), to = from + dir * (pixels / view.pixelsPerUnit);
      const double head = std::min(6.0, 0.4 * pixels) / view.pixelsPerUnit;
      arrows_.line(from, to, colours[k]);
      arrows_.line(to, to - head * (dir + 0.5 * side), colours[k]);
      arrows_.line(to, to - head * (dir - 0.5 * side), colours[k]);
    }
}

void Renderer::collectParticles(const Simulation& simulation, const ViewTransform& view) {
  const particles::ParticleSystem& system = simulation.system();
  const int grabbed = simulation.mouseSpring() ? simulation.mouseSpring()->particle() : -1;
  const particles::Phase phase = phaseOf(system);
  const int diameter = pointDiameter(phase, view.pixelsPerUnit);
  for (int i = 0; i < system.size(); ++i) {
    const bool marked = i == grabbed || system.pinned(i);
    if (!marked && !drawing_.particlesDrawn) continue;
    const Rgb colour = i == grabbed            ? palette::grabbedParticle
                       : system.pinned(i)      ? palette::pinnedParticle
                                               : palette::particle;
    // A collidable particle also shows its collision disc, faintly, under the mesh.
    if (system.collidable(i)) {
      const int disc = pixels(2.0 * system.radii()[i] * view.pixelsPerUnit, 0, 4096);
      if (disc > diameter) discsBySize_[disc].add(phase.position(i), colour, 56);
    }
    pointsBySize_[marked ? diameter + 2 : diameter].add(phase.position(i), colour);
  }
}

}  // namespace demo
