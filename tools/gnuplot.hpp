#pragma once
/// The gnuplot program the report commands draw with: the one CMake found (CUSHION_GNUPLOT) if it is
/// still there, else the first on PATH, else "" (plots are then skipped with a message).
#include <string>

#include "calibration/plot.hpp"

namespace cushion::tools {

inline std::string gnuplot_path() {
#ifdef CUSHION_GNUPLOT
  return cushion::calibration::find_gnuplot(CUSHION_GNUPLOT);
#else
  return cushion::calibration::find_gnuplot();
#endif
}

}  // namespace cushion::tools
