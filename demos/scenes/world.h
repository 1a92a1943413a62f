#pragma once
// The world and the pieces several scenes share. Units are SI: metres,
// kilograms, seconds. Unless a scene says otherwise it uses the view [−1, 1]²
// (2 m across), Earth's gravity downward and the solver's feedback k_s = 60,
// k_d = 10 (particles::SolverSettings defaults).
#include <Eigen/Core>

#include "particles/constants.h"
#include "particles/constraints/rod.h"
#include "particles/particle_system.h"

namespace scenes {

// m/s², downward: the default preset's gravity.
constexpr double kEarthGravity = 9.81;
// The seed report's gravity (preset "seed"): it lowered 9.81 to 0.05 because
// its particles fell "unrealistically fast" at one step per frame, which
// slowed every motion by √(9.81/0.05) ≈ 14.
constexpr double kSeedGravity = 0.05;

constexpr double radians(double degrees) { return degrees * particles::kPi / 180.0; }

// Adds uniform gravity g downward (world units / s²); nothing when g = 0, so
// a weightless scene carries no gravity force.
void addGravity(particles::ParticleSystem& system, double g);

// Adds links + 1 particles of the given mass evenly from start to end, joined
// by links rods of length |end − start| / links; returns the first index.
int addRodChain(particles::ParticleSystem& system, const Eigen::Vector2d& start,
                const Eigen::Vector2d& end, int links, double mass, particles::RodForm form);

}  // namespace scenes
