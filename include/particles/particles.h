#pragma once
// The whole engine in one include: the particle system, its forces,
// constraints and colliders, and the integrators by name (integrator.h's
// table: makeIntegrator("rk4")).
//   #include <particles/particles.h>
#include "particles/collider.h"
#include "particles/collision.h"
#include "particles/constants.h"
#include "particles/constraint.h"
#include "particles/constraint_solver.h"
#include "particles/constraints/circular_wire.h"
#include "particles/constraints/line.h"
#include "particles/constraints/rod.h"
#include "particles/divergence.h"
#include "particles/force.h"
#include "particles/forces/angular_spring.h"
#include "particles/forces/drag.h"
#include "particles/forces/gravity.h"
#include "particles/forces/mouse_spring.h"
#include "particles/forces/spring.h"
#include "particles/forces/wind.h"
#include "particles/grab.h"
#include "particles/integrator.h"
#include "particles/particle_system.h"
#include "particles/phase.h"
#include "particles/solver_names.h"
#include "particles/step_stats.h"
#include "particles/tearing.h"
#include "particles/threads.h"
