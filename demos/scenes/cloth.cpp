#include "scenes/cloth.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "particles/check.h"
#include "particles/constraints/line.h"
#include "particles/forces/spring.h"
#include "scenes/param_fields.h"
#include "scenes/world.h"

namespace scenes {

void ClothParams::validate() const {
  requireAtLeast("width", width, 2);
  requireAtLeast("height", height, 2);
  if (links != 4 && links != 8)
    throw std::invalid_argument("links must be 4 or 8, got " + std::to_string(links));
  particles::requirePositive("rest", rest);
  particles::requireNonNegative("stiffness", stiffness);
  particles::requireNonNegative("damping", damping);
  particles::requirePositive("mass", mass);
  particles::requireFinite("gravity", gravity);
}

Scene buildCloth(const ClothParams& p) {
  Scene scene;
  scene.name = "cloth";
  scene.dt = 0.01;
  scene.system = std::make_unique<particles::ParticleSystem>();
  particles::ParticleSystem& s = *scene.system;

  // Layout in units of the cloth's extent L, so that a larger grid gets the
  // same stage; the default 10×10 cloth (L = 0.45) fits the view [−1, 1]².
  const double clothWidth = (p.width - 1) * p.rest, clothHeight = (p.height - 1) * p.rest;
  const double L = std::max(clothWidth, clothHeight);
  const double half = std::max(1.0, 2.2 * L);
  const Eigen::Vector2d topLeft(-0.5 * clothWidth, 0.6 * half);

  std::vector<Eigen::Vector2d> positions;
  for (int row = 0; row < p.height; ++row)
    for (int col = 0; col < p.width; ++col)
      positions.push_back(topLeft + p.rest * Eigen::Vector2d(col, -row));
  s.addParticles(positions, std::vector<double>(positions.size(), p.mass));
  const auto id = [&](int row, int col) { return row * p.width + col; };

  auto link = [&](int i, int j, double rest) {
    s.addForce(std::make_unique<particles::SpringForce>(i, j, rest, p.stiffness, p.damping));
    s.addCollisionEdge(i, j);  // the springs, not only the particles, catch on the nail
  };
  const double diagonal = std::sqrt(2.0) * p.rest;
  for (int row = 0; row < p.height; ++row)
    for (int col = 0; col < p.width; ++col) {
      if (col + 1 < p.width) link(id(row, col), id(row, col + 1), p.rest);
      if (row + 1 < p.height) link(id(row, col), id(row + 1, col), p.rest);
      if (p.links == 8 && row + 1 < p.height && col + 1 < p.width) {
        link(id(row, col), id(row + 1, col + 1), diagonal);
        link(id(row, col + 1), id(row + 1, col), diagonal);
      }
    }
  addGravity(s, p.gravity);

  // The curtain rail: the top row slides on the horizontal line through it.
  for (int col = 0; col < p.width; ++col)
    s.addConstraint(std::make_unique<particles::LineConstraint>(id(0, col), topLeft, 0.0));

  // A big wall left of the cloth, from just below the rail to below the hem
  // of the cloth hanging stretched under its weight (about twice its rest
  // height at the defaults), and a small nail to the right, near the top.
  s.addCollider(particles::Collider::box(Eigen::Vector2d(topLeft.x() - 0.9 * L, topLeft.y() - 2.6 * L),
                                        Eigen::Vector2d(topLeft.x() - 0.3 * L, topLeft.y() - 0.3 * L)));
  const Eigen::Vector2d nail(-topLeft.x() + 0.3 * L, topLeft.y() - 0.4 * L);
  s.addCollider(particles::Collider::box(nail, nail + Eigen::Vector2d::Constant(0.05 * L)));

  scene.viewMin = Eigen::Vector2d::Constant(-half);
  scene.viewMax = Eigen::Vector2d::Constant(half);
  return scene;
}

}  // namespace scenes
