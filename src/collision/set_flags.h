#pragma once
// The indices of the set flags in a byte array where most are 0.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

namespace particles::contact {

// Appends the i with flags[i] ≠ 0, ascending; eight flags are tested at a time.
inline void appendSetFlags(const std::vector<char>& flags, std::vector<int>& out) {
  const int count = static_cast<int>(flags.size());
  for (int word = 0; word < count; word += 8) {
    const int end = std::min(count, word + 8);
    if (end - word == 8) {
      std::uint64_t eight;
      std::memcpy(&eight, flags.data() + word, 8);
      if (eight == 0) continue;
    }
    for (int i = word; i < end; ++i)
      if (flags[i]) out.push_back(i);
  }
}

}  // namespace particles::contact
