#include "scenes/cloth.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "particles/check.h"
#include "particles/constraints/line.h"
#include "particles/forces/drag.h"
#include "particles/forces/face_area.h"
#include "particles/forces/spring.h"
#include "scene_limits.h"
#include "scenes/param_fields.h"
#include "scenes/world.h"

namespace scenes {

void ClothParams::validate() const {
  requireAtLeast("width", width, 2);
  requireAtLeast("height", height, 2);
  requireWithinLimit("width*height particles", static_cast<long long>(width) * height, SceneLimits::particles);
  if (links != 4 && links != 8)
    throw std::invalid_argument("links must be 4 or 8, got " + std::to_string(links));
  particles::requirePositive("rest", rest);
  particles::requireNonNegative("stiffness", stiffness);
  particles::requireNonNegative("damping", damping);
  particles::requirePositive("mass", mass);
  particles::requireFinite("gravity", gravity);
  particles::requireInRange("swing", swing, -80.0, 80.0);
  particles::requireNonNegative("drag", drag);
  if (edgeContacts != 0 && edgeContacts != 1)
    throw std::invalid_argument("edge-contacts must be 0 or 1, got " + std::to_string(edgeContacts));
  particles::requireNonNegative("area-stiffness", areaStiffness);
  particles::requireInRange("area-floor", areaFloor, 0.0, 1.0);
  validateWindTear();
}

ClothParams ClothParams::seed() {
  ClothParams p;
  p.width = 10;
  p.height = 10;
  p.links = 4;
  p.rest = 0.05;
  p.stiffness = 0.9;
  p.damping = 0.6;
  p.mass = 0.2;
  p.gravity = kSeedGravity;
  p.swing = 0.0;
  p.drag = 0.0;
  p.edgeContacts = 0;
  p.areaStiffness = 0.0;
  p.dt = 0.01;
  return p;
}

Scene buildCloth(const ClothParams& p) {
  Scene scene;
  scene.name = "cloth";
  scene.dt = p.dt;
  scene.system = std::make_unique<particles::ParticleSystem>();
  particles::ParticleSystem& s = *scene.system;

  // Layout in units of the cloth's extent L, so that a larger grid gets the
  // same stage; the default 10×10 cloth (L = 0.45) fits the view [−1, 1]².
  const double clothWidth = (p.width - 1) * p.rest, clothHeight = (p.height - 1) * p.rest;
  const double L = std::max(clothWidth, clothHeight);
  const double half = std::max(1.0, 2.2 * L);
  const Eigen::Vector2d topLeft(-0.5 * clothWidth, 0.6 * half);

  // Row r hangs r rest lengths down its column; every spring starts at its
  // rest length (cloth.h). The 4-way cloth's columns are turned by the swing
  // (a shear its springs do not resist); the 8-way cloth hangs straight and
  // its rows start moving at ω times their depth.
  const double swing = radians(p.swing);
  const bool swingByVelocity = p.links == 8;
  const Eigen::Vector2d down =
      swingByVelocity ? Eigen::Vector2d(0.0, -1.0) : Eigen::Vector2d(std::sin(swing), -std::cos(swing));
  std::vector<Eigen::Vector2d> positions;
  for (int row = 0; row < p.height; ++row)
    for (int col = 0; col < p.width; ++col)
      positions.push_back(topLeft + p.rest * (col * Eigen::Vector2d::UnitX() + row * down));
  s.addParticles(positions, std::vector<double>(positions.size(), p.mass));
  if (swingByVelocity && clothHeight > 0.0) {
    const double omega = std::copysign(std::sqrt(3.0 * p.gravity * (1.0 - std::cos(swing)) / clothHeight), swing);
    for (int row = 0; row < p.height; ++row)
      for (int col = 0; col < p.width; ++col)
        s.setVelocity(row * p.width + col, Eigen::Vector2d(omega * row * p.rest, s.velocity(row * p.width + col).y()));
  }
  const auto id = [&](int row, int col) { return row * p.width + col; };

  // Grid cells as faces, counter-clockwise: top-left, bottom-left, bottom-right, top-right.
  for (int row = 0; row + 1 < p.height; ++row)
    for (int col = 0; col + 1 < p.width; ++col)
      scene.faces.push_back({id(row, col), id(row + 1, col), id(row + 1, col + 1), id(row, col + 1)});
  scene.edgeContacts = p.edgeContacts == 1;

  auto link = [&](int i, int j, double rest) {
    s.addForce(std::make_unique<particles::SpringForce>(i, j, rest, p.stiffness, p.damping));
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
  // The faces' area floor (cloth.h): every cell, its rest area rest².
  if (p.areaStiffness > 0.0) {
    std::vector<particles::AreaFace> areaFaces;
    for (const std::array<int, 4>& face : scene.faces)
      areaFaces.push_back({std::vector<int>(face.begin(), face.end()), p.rest * p.rest});
    s.addForce(std::make_unique<particles::FaceAreaForce>(std::move(areaFaces), p.areaStiffness, p.areaFloor));
  }
  addGravity(s, p.gravity);
  if (p.drag > 0.0) s.addForce(std::make_unique<particles::DragForce>(p.drag));

  // The curtain rail: the top row slides on the horizontal line through it,
  // between two end stops 0.8 L beyond the cloth's ends at rest, which the
  // wind pushes the curtain against instead of off the rail.
  for (int col = 0; col < p.width; ++col)
    s.addConstraint(std::make_unique<particles::LineConstraint>(id(0, col), topLeft, 0.0));
  const double stop = 0.04 * L;
  for (const double end : {topLeft.x() - 0.8 * L - stop, -topLeft.x() + 0.8 * L})
    s.addCollider(particles::Collider::box(Eigen::Vector2d(end, topLeft.y() - stop), Eigen::Vector2d(end + stop, topLeft.y() + stop)));

  // A big wall left of the cloth, from just below the rail to below the hem
  // of the cloth hanging stretched under its weight (about twice its rest
  // height under the seed preset), and a small nail to the right, near the
  // top. With edgeContacts the cloth's face edges, not only its particles,
  // meet them (faceEdges), so the nail can catch the cloth between two particles.
  s.addCollider(particles::Collider::box(Eigen::Vector2d(topLeft.x() - 0.9 * L, topLeft.y() - 2.6 * L),
                                        Eigen::Vector2d(topLeft.x() - 0.3 * L, topLeft.y() - 0.3 * L)));
  const Eigen::Vector2d nail(-topLeft.x() + 0.3 * L, topLeft.y() - 0.4 * L);
  s.addCollider(particles::Collider::box(nail, nail + Eigen::Vector2d::Constant(0.05 * L)));
  if (scene.edgeContacts)
    for (const std::array<int, 2>& edge : faceEdges(scene)) s.addCollisionEdge(edge[0], edge[1]);
  scene.windEdges = faceEdges(scene);
  p.addWindAndTearing(s, scene.windEdges);

  // The wall, the rail between its end stops and the cloth hanging from it,
  // stretched to twice its rest height at most (the seed's soft cloth).
  const double margin = 0.15 * L;
  scene.viewMin = Eigen::Vector2d(topLeft.x() - 0.9 * L - margin, topLeft.y() - std::max(2.6 * L, 2.0 * clothHeight) - margin);
  scene.viewMax = Eigen::Vector2d(-topLeft.x() + 0.85 * L + margin, topLeft.y() + margin);
  return scene;
}

ClothParams stiffClothParams(int size) {
  ClothParams p;
  p.width = p.height = size;
  p.links = 8;
  p.stiffness = 4e5;
  p.damping = 0.5;
  p.gravity = 9.8;
  p.swing = 0.0;  // released hanging straight, no air drag, no edge contacts
  p.drag = 0.0;
  p.edgeContacts = 0;
  p.areaStiffness = 0.0;
  p.validate();
  return p;
}

}  // namespace scenes
