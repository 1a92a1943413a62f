#include "particles/cancel.h"

namespace particles {

namespace {
std::atomic<const std::atomic<bool>*> gFlag{nullptr};
}  // namespace

void setCancelFlag(const std::atomic<bool>* flag) { gFlag.store(flag); }

bool cancelRequested() {
  const std::atomic<bool>* flag = gFlag.load(std::memory_order_relaxed);
  return flag != nullptr && flag->load(std::memory_order_relaxed);
}

}  // namespace particles
