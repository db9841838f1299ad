#pragma once
/// Follower pressure on element faces (StepSpec::pressures, ABAQUS *DLOAD Pn with NLGEOM): traction
/// t = -p n on the current face, n the outward normal, p > 0 pushing into the solid. Residual and
/// its (unsymmetric) tangent, integrated on the face in the element's own shape functions:
///   r_a += p int N_a (x_s x x_t) ds dt,
///   dr_a/dx_b = p int N_a (dN_b/dt [x_s]x - dN_b/ds [x_t]x) ds dt,
/// with [v]x the cross-product matrix and (s, t) the face's natural coordinates (Gauss 2x2 on hex8
/// faces, 3x3 on hex20 faces, collapsed 3x3 Gauss on tet faces).
#include <memory>

#include "solver/analysis/step.hpp"

namespace cushion::solver {

/// Adds the residual of pressure p [MPa] on face `face` at displacements u (full vector [mm]) to r (full,
/// [N]) and, if K is non-null, its tangent to K (free-DOF equations of `dofs`).
void add_face_pressure(const mesh::Mesh& mesh, const mesh::Face& face, double p, const Eigen::VectorXd& u,
                       const DofMap& dofs, Eigen::VectorXd& r, SparseMatrix* K);

/// The pressure contributor of a step on the DOFs `dofs` of its system, or nullptr without pressures.
std::shared_ptr<ResidualContributor> step_pressures(const AnalysisContext& ctx, const StepSpec& step, const DofMap& dofs);

/// True if some step has pressures (their tangent is unsymmetric: LU).
bool case_has_pressure(const CaseSpec& spec);

}  // namespace cushion::solver
