#pragma once
/// Small text helpers shared by the mesh readers (.inp, selectors, STL).
#include <string>

namespace cushion::mesh {

/// `s` without leading and trailing blanks (space, tab, CR, LF).
inline std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

}  // namespace cushion::mesh
