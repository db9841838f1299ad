#pragma once
/// ABAQUS material cards for a visco-hyperfoam material (for users who still run ABAQUS):
///   *MATERIAL, NAME=..
///   *DENSITY                         (t/mm^3, in the mm-N-s-t unit system)
///   *HYPERFOAM, N=n, MODULI=LONG TERM
///   mu_1, alpha_1, mu_2, alpha_2, ...   then nu_1, nu_2, ...  (8 values per line, as ABAQUS reads them)
///   *VISCOELASTIC, TIME=PRONY
///   g_i, k_i = g_i, tau_i             (one line per term; same relaxation in shear and bulk)
/// Stresses are in MPa (N/mm^2): the whole deck must use mm, N, s, t.
#include <string>

#include "calibration/fit_model.hpp"

namespace cushion::calibration {

/// The cards as text; `comment` lines are written first as "** ..." comment lines.
std::string abaqus_cards(const ViscoHyperfoam& material, const std::string& name, double density,
                         const std::string& comment);

}  // namespace cushion::calibration
