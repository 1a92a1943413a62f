#include "xpbd/attachment.h"

namespace particles {

void projectAttachment(const CompliantAttachment& c, const Eigen::VectorXd& w, const Eigen::VectorXd& xn,
                       Eigen::VectorXd& x, Eigen::Vector2d& lambda) {
  const double weight = w[c.i];
  if (weight == 0.0) return;  // pinned: nothing to move
  const double inverse = inverseDenominator(weight, c.compliance);
  for (int r = 0; r < 2; ++r) {
    const int q = 2 * c.i + r;
    const double dl = multiplierStep(x[q] - c.target[r], x[q] - xn[q], c.compliance, lambda[r], inverse);
    lambda[r] += dl;
    x[q] += weight * dl;
  }
}

}  // namespace particles
