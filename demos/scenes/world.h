#pragma once
// The report's world and the pieces several scenes share. Unless a scene says
// otherwise it uses the view [−1, 1]², gravity 0.05 downward and the solver's
// feedback k_s = 60, k_d = 10 (particles::SolverSettings defaults).
#include <Eigen/Core>

#include "particles/constraints/rod.h"
#include "particles/particle_system.h"

namespace scenes {

// World units / s², downward. The report lowered Earth's 9.81 to 0.05 because
// its particles fell "unrealistically fast" at one step per frame.
constexpr double kWorldGravity = 0.05;

constexpr double kPi = 3.14159265358979323846;
constexpr double radians(double degrees) { return degrees * kPi / 180.0; }

// Adds uniform gravity g downward (world units / s²); nothing when g = 0, so
// a weightless scene carries no gravity force.
void addGravity(particles::ParticleSystem& system, double g);

// Adds links + 1 particles of the given mass evenly from start to end, joined
// by links rods of length |end − start| / links; returns the first index.
int addRodChain(particles::ParticleSystem& system, const Eigen::Vector2d& start,
                const Eigen::Vector2d& end, int links, double mass, particles::RodForm form);

}  // namespace scenes
