#pragma once
// XPBD's settings (particles/integrators/xpbd.h), held in IntegratorSettings
// so that makeIntegrator reaches them as it reaches every other scheme's.
namespace particles {

struct XpbdSettings {
  // A step of dt is `substeps` substeps of h = dt/substeps, each with
  // `iterations` Gauss–Seidel passes over the constraints. Macklin et al.
  // 2019 favour many substeps of one pass; the defaults are measured by
  // `particle-lab small-steps` (report, "Small steps").
  int substeps = 20;     // in [1, 100000]
  int iterations = 1;    // in [1, 10000]
  // Solve each straight line of springs hanging from a held particle
  // directly, before each pass's Gauss–Seidel sweep (xpbd/hanging_lines.h):
  // a hanging cloth or strand then holds its length with a few substeps.
  bool lines = false;

  void validate() const;  // throws naming the bad field
};

}  // namespace particles
