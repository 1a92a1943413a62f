#include "particles/cancel.h"

namespace particles {

namespace detail {
std::atomic<const std::atomic<bool>*> cancelFlag{nullptr};
}  // namespace detail

void setCancelFlag(const std::atomic<bool>* flag) { detail::cancelFlag.store(flag); }

}  // namespace particles
