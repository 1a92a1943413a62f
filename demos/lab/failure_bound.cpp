#include "lab/failure_bound.h"

#include <cmath>
#include <stdexcept>

#include <boost/math/special_functions/beta.hpp>

#include "output/format_number.h"

namespace lab {

namespace {

void requireConfidence(double confidence) {
  if (!(confidence > 0.0 && confidence < 1.0))
    throw std::invalid_argument("confidence must be in (0, 1), got " + output::formatNumber(confidence));
}

void requireCounts(long failures, long runs) {
  if (runs < 0 || failures < 0 || failures > runs)
    throw std::invalid_argument("failure bound: need 0 <= failures <= runs, got " + std::to_string(failures) +
                                " of " + std::to_string(runs));
}

}  // namespace

double failureUpperBound(long failures, long runs, double confidence) {
  requireConfidence(confidence);
  requireCounts(failures, runs);
  if (failures == runs) return 1.0;
  // k = 0 in closed form (exact where the quantile's iteration would round).
  if (failures == 0) return -std::expm1(std::log1p(-confidence) / static_cast<double>(runs));
  return boost::math::ibeta_inv(static_cast<double>(failures + 1), static_cast<double>(runs - failures), confidence);
}

double failureLowerBound(long failures, long runs, double confidence) {
  requireConfidence(confidence);
  requireCounts(failures, runs);
  if (failures == 0) return 0.0;
  if (failures == runs) return std::pow(1.0 - confidence, 1.0 / static_cast<double>(runs));
  return boost::math::ibeta_inv(static_cast<double>(failures), static_cast<double>(runs - failures + 1),
                                1.0 - confidence);
}

long runsForBound(double bound, double confidence) {
  requireConfidence(confidence);
  if (!(bound > 0.0 && bound < 1.0))
    throw std::invalid_argument("failure bound must be in (0, 1), got " + output::formatNumber(bound));
  // (1 − bound)^N ≤ 1 − c; the small slack keeps an exact N from rounding up.
  return static_cast<long>(std::ceil(std::log1p(-confidence) / std::log1p(-bound) - 1e-9));
}

std::string boundText(const FailureCount& count) {
  return "p ≤ " + output::formatGeneral(count.upperBound(), 2);
}

std::string countText(const FailureCount& count) {
  return std::to_string(count.failures) + "/" + std::to_string(count.runs);
}

}  // namespace lab
