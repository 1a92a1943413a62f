#include "vector_kernels.h"

namespace particles {

PARTICLES_VECTOR_CLONES
void addTerms(int count, const double* from, double* to) {
#pragma omp simd
  for (int u = 0; u < count; ++u) to[u] += from[u];
}

PARTICLES_VECTOR_CLONES
void subtractTerms(int count, const double* from, double* to) {
#pragma omp simd
  for (int u = 0; u < count; ++u) to[u] -= from[u];
}

}  // namespace particles
