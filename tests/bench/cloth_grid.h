#pragma once
// The benchmarks' 8-way spring cloth: width × height particles of mass 0.2 at
// `spacing`, row 0 on top and pinned; springs to the right and down
// neighbours (rest spacing) and to both lower diagonals (rest √2·spacing);
// gravity and a little drag.
#include <cmath>
#include <memory>
#include <vector>

#include "particles/forces/drag.h"
#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "particles/particle_system.h"

namespace bench {

constexpr double kClothStiffness = 50.0, kClothDamping = 0.5;  // N/m, N s/m
constexpr double kClothGravity = -9.81, kClothDrag = 0.01;     // m/s², kg/s
constexpr double kClothMass = 0.2;                              // kg

inline particles::ParticleSystem clothGrid(int width, int height, double spacing) {
  using Eigen::Vector2d;
  particles::ParticleSystem system;
  std::vector<Vector2d> positions;
  for (int row = 0; row < height; ++row)
    for (int col = 0; col < width; ++col) positions.emplace_back(col * spacing, -row * spacing);
  system.addParticles(positions, std::vector<double>(positions.size(), kClothMass));
  auto id = [&](int row, int col) { return row * width + col; };
  for (int col = 0; col < width; ++col) system.setPinned(id(0, col), true);
  const double diagonal = std::sqrt(2.0) * spacing;
  for (int row = 0; row < height; ++row)
    for (int col = 0; col < width; ++col) {
      auto spring = [&](int r, int c, double rest) {
        system.addForce(std::make_unique<particles::SpringForce>(id(row, col), id(r, c), rest, kClothStiffness,
                                                                 kClothDamping));
      };
      if (col + 1 < width) spring(row, col + 1, spacing);
      if (row + 1 < height) spring(row + 1, col, spacing);
      if (row + 1 < height && col + 1 < width) spring(row + 1, col + 1, diagonal);
      if (row + 1 < height && col > 0) spring(row + 1, col - 1, diagonal);
    }
  system.addForce(std::make_unique<particles::GravityForce>(Vector2d(0.0, kClothGravity)));
  system.addForce(std::make_unique<particles::DragForce>(kClothDrag));
  return system;
}

}  // namespace bench
