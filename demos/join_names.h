#pragma once
#include <string>

namespace scenes {

// "a, b, c" from the entries of a table (scenes, integrators, codecs), for
// messages that list what is valid. name(entry) gives an entry's name.
template <class Table, class Name>
std::string joinNames(const Table& table, Name name) {
  std::string names;
  for (const auto& entry : table) {
    names += names.empty() ? "" : ", ";
    names += name(entry);
  }
  return names;
}

template <class Table>
std::string joinNames(const Table& table) {
  return joinNames(table, [](const auto& entry) { return std::string(entry.name); });
}

}  // namespace scenes
