#include "format_number.h"

namespace scenes {

std::string plural(long long count, const std::string& noun, const std::string& pluralNoun) {
  return std::to_string(count) + " " + (count == 1 ? noun : pluralNoun.empty() ? noun + "s" : pluralNoun);
}

}  // namespace scenes
