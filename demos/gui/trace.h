#pragma once
// The last few seconds of energy and constraint error, for the panel's plots.
#include <vector>

namespace demo {

class Trace {
 public:
  static constexpr int capacity = 600;  // frames kept (10 s at 60 frames/s)

  void add(double energy, double constraintError) {
    if (static_cast<int>(energy_.size()) == capacity) {
      energy_.erase(energy_.begin());
      constraintError_.erase(constraintError_.begin());
    }
    energy_.push_back(static_cast<float>(energy));
    constraintError_.push_back(static_cast<float>(constraintError));
  }
  void clear() { energy_.clear(); constraintError_.clear(); }
  const std::vector<float>& energy() const { return energy_; }
  const std::vector<float>& constraintError() const { return constraintError_; }

 private:
  std::vector<float> energy_, constraintError_;
};

}  // namespace demo
