#pragma once
/// What one output frame holds, as plain arrays in internal units, so that result output does not
/// depend on the solver's internals. The writer converts units and names every array with its unit.
#include <string>
#include <vector>

#include "material/tensor.hpp"

namespace cushion::solver {

/// An extra named array (e.g. contact pressure). Entity-major: values[i * components + c].
struct NamedField {
  std::string name;             ///< array name including its unit, e.g. "contact_pressure_kPa"
  int components = 1;           ///< 1 scalar, 3 vector, 6 symmetric tensor (XX YY ZZ XY YZ XZ)
  std::vector<double> values;   ///< written as given (no unit conversion)
};

/// One frame. Empty optional vectors are simply not written.
struct FrameData {
  double time = 0.0;                         ///< total time [s]
  std::vector<Vec3> displacement;            ///< per node [mm] (required), reference frame axes
  std::vector<Vec3> reaction_force;          ///< per node [N], zero at free DOFs (optional)
  std::vector<Mat3> cauchy_stress;           ///< per element, average over integration points [MPa], current frame
  std::vector<Mat3> deformation_gradient;    ///< per element, average over integration points [-]
  std::vector<double> viscous_stress_norm;   ///< per element, |sigma_visc| Frobenius norm of the
                                             ///< viscous (Prony) part of the Cauchy stress [MPa]
  std::vector<NamedField> point_fields;      ///< extra per-node arrays
  std::vector<NamedField> cell_fields;       ///< extra per-element arrays
};

}  // namespace cushion::solver
