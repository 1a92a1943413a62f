#pragma once
// The largest scene particle-lab and the demo accept, in one place: the scene
// table's builders and the scene-file reader check these before allocating,
// so that an absurd size is one line and exit 2 rather than an exhausted
// memory or a step that never ends. Documented in demos/scenes/FORMAT.md
// (Hostile input, Limits).
#include <cstddef>
#include <string>

namespace scenes {

struct SceneLimits {
  static constexpr std::size_t fileBytes = 64u << 20;     // a scene file, bytes (64 MiB)
  static constexpr int nestingDepth = 64;                 // JSON arrays and objects inside each other
  // Values of a scene file's JSON document (every number, string, boolean,
  // null, array and object counts one): the document takes at most about
  // 100 bytes of memory a value (json_parse.h), and the largest built-in
  // scene's export (a 316×316 8-way cloth with wind and edge contacts) holds
  // 5.2 million.
  static constexpr long long jsonValues = 8000000;
  static constexpr long long particles = 100000;          // particles in one scene
  static constexpr long long forces = 1000000;            // force objects in one scene
  static constexpr long long constraints = 100000;        // constraints in one scene
  // Constraints sharing one particle: they form a dense block of J W Jᵀ, so
  // the solve's cost grows with the square of this count.
  static constexpr long long constraintsPerParticle = 64;
  static constexpr long long walls = 1000;                // walls (each is tested against every particle)
};

// Throws std::invalid_argument "<what> = <count> exceeds the limit of <limit>"
// (what names the parameters, e.g. "width*height particles") unless count <= limit.
void requireWithinLimit(const std::string& what, long long count, long long limit);

}  // namespace scenes
