#pragma once
// The one place the laboratory builds its scenes. The lab reproduces the seed
// report's parameters (test chain of rods of length 0.05 under g = 0.05 and
// the seed's cloth, oscillator and pendulum), whatever the demo's defaults
// become: it builds the seed preset of every scene here.
#include <map>
#include <string>

#include "scene.h"

namespace lab {

// Builds a built-in scene from its preset "seed" (the seed report's
// parameters and time step) with `overrides` on top; throws
// std::invalid_argument like scenes::buildScene.
scenes::Scene buildLabScene(const std::string& name, const std::map<std::string, std::string>& overrides = {});

// Ensemble member `member` of a scene: member 0 is the scene as built; member
// k > 0 moves every unpinned particle by a fixed pseudo-random offset of
// length relativeSize × D (D the diagonal of the initial bounding box), the
// same offsets for the same k on every run and thread.
void perturbStart(scenes::Scene& scene, int member, double relativeSize = 1e-6);

}  // namespace lab
