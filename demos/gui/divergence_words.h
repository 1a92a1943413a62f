#pragma once
// Why a pane stopped, said in words a user acts on: what happened in the
// simulation, without the engine's names for it (particles::Divergence::
// message() keeps those, for the runner and the laboratory).
#include <string>

#include "particles/divergence.h"

namespace demo {

// One clause, e.g. "a particle struck the walls more often in one step than
// the contact pass follows: it moves too fast for this step"; brief: a few
// words for a narrow place ("a particle struck the walls too often").
std::string divergenceInWords(const particles::Divergence& divergence, bool brief = false);

// What the keys can do about it, for every divergence alike.
inline const char* divergenceRemedy() { return "- halves dt, i tries another integrator, r resets, b rewinds"; }

}  // namespace demo
