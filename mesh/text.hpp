#pragma once
/// Small text helpers shared by the mesh readers (.inp, selectors, STL).
#include <algorithm>
#include <string>

#include "io/text_support.hpp"

namespace cushion::mesh {

/// `s` without leading and trailing blanks (space, tab, CR, LF).
inline std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

/// The entry of the name-keyed map `sets` whose key is `name`, else the first whose key equals it ignoring case
/// (ABAQUS names are case-insensitive), else end.
template <class Map>
auto find_name(Map& sets, const std::string& name) -> decltype(sets.find(name)) {
  const auto exact = sets.find(name);
  if (exact != sets.end()) return exact;
  const std::string key = io::upper_case(name);
  return std::find_if(sets.begin(), sets.end(), [&](const auto& entry) { return io::upper_case(entry.first) == key; });
}

}  // namespace cushion::mesh
