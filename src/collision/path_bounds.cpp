#include <algorithm>

#include "particles/collision.h"
#include "vector_kernels.h"

namespace particles {

namespace {
// Minima, maxima and a sum that is 0 when every coordinate is finite and NaN
// otherwise (x − x is NaN at ±∞ and NaN), over particles [begin, end).
PARTICLES_VECTOR_CLONES void boxOf(const double* x0, const double* x, const double* radius, int begin, int end,
                                   double* lo, double* hi, double* largest, double* check) {
  double loX = lo[0], loY = lo[1], hiX = hi[0], hiY = hi[1], r = *largest, sum = 0.0;
#pragma omp simd reduction(min : loX, loY) reduction(max : hiX, hiY, r) reduction(+ : sum)
  for (int i = begin; i < end; ++i) {
    const double ax = x0[2 * i], ay = x0[2 * i + 1], bx = x[2 * i], by = x[2 * i + 1];
    loX = std::min(loX, std::min(ax, bx));
    loY = std::min(loY, std::min(ay, by));
    hiX = std::max(hiX, std::max(ax, bx));
    hiY = std::max(hiY, std::max(ay, by));
    r = std::max(r, radius[i]);
    sum += (ax - ax) + (ay - ay) + (bx - bx) + (by - by);
  }
  lo[0] = loX;
  lo[1] = loY;
  hi[0] = hiX;
  hi[1] = hiY;
  *largest = r;
  *check = sum;
}
}  // namespace

PathBounds PathBounds::of(const double* x0, const double* x, const double* radius, int begin, int end) {
  PathBounds b;
  double check = 0.0;
  boxOf(x0, x, radius, begin, end, b.lo, b.hi, &b.radius, &check);
  b.finite = check == 0.0;
  return b;
}

void PathBounds::merge(const PathBounds& other) {
  for (int d = 0; d < 2; ++d) {
    lo[d] = std::min(lo[d], other.lo[d]);
    hi[d] = std::max(hi[d], other.hi[d]);
  }
  radius = std::max(radius, other.radius);
  finite = finite && other.finite;
}

}  // namespace particles
