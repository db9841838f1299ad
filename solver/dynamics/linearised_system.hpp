#pragma once
/// Small-amplitude linearisation of a solid model about a base state (the committed end of a static
/// step), for steady-state dynamics, modal analysis and the Rayleigh damping of the dynamic step.
///
/// Complex tangent stiffness, element by element (docs/physics.md 3.2):
///   K*(w) = int B^T C*(w) B dV0 + int (g_a . S_geo g_b) I dV0   (+ the F-bar terms of the kernel),
/// C*(w) = Material::complex_tangent(F_base, w) at every quadrature point (the Prony part scales the
/// long-term tangent about the base), S_geo the REAL base-state PK2 stress, unscaled by the Prony
/// factor [A]. The element kernel (integrate_element) is reused unchanged: a frozen-tangent material
/// returns S_geo and Re C* (real part), then S = 0 and Im C* (imaginary part, no geometric term).
///
/// Base stress S_geo (BaseStress, solver/case/steady_state_spec.hpp):
///   relaxed (default, ABAQUS *STEADY STATE DYNAMICS convention): the long-term stress at F_base, i.e.
///     the material integrated from its committed state over an infinitely long hold at F_base;
///   as_left: the committed total stress at the end of the previous step (viscous overstress included).
/// The displacement field of the base state is the committed one in both cases.
///
/// All matrices live on ALL node DOFs (3 per node, dof = 3 node + c, nothing eliminated), so the
/// caller can partition free / prescribed DOFs and read reactions at any DOF.
#include <complex>
#include <memory>
#include <vector>

#include "solver/assembler.hpp"
#include "solver/case/damping.hpp"
#include "solver/case/steady_state_spec.hpp"

namespace cushion::solver::dynamics {

/// Complex sparse matrix on all DOFs [N/mm].
using ComplexMatrix = Eigen::SparseMatrix<std::complex<double>>;
/// Complex 3 x 3 tensor (complex amplitude of a harmonic tensor field).
using Mat3c = Eigen::Matrix<std::complex<double>, 3, 3>;

/// Rayleigh damping matrix C = alpha M + beta K [N s/mm] from the mass M [t] and a stiffness K [N/mm]
/// of the same size (the dynamic step's and the steady state's; Damping::structural is not used).
SparseMatrix damping_matrix(const Damping& damping, const SparseMatrix& M, const SparseMatrix& K);

/// Base state of one quadrature point.
struct PointBase {
  Mat3 F = Mat3::Identity();  ///< deformation gradient seen by the material (F_bar for F-bar) [-]
  Vec6 S_geo = Vec6::Zero();  ///< PK2 stress of the geometric stiffness [MPa], reference frame, Voigt
};

/// Point base states at the full displacement u_base [mm] from the committed state of `state`
/// (state is not modified). Throws std::runtime_error if a material point fails there.
std::vector<PointBase> base_point_states(const Assembler& assembler, const StateStore& state,
                                         const Eigen::VectorXd& u_base, BaseStress stress);

/// The linearised model: complex stiffness at any frequency, long-term real stiffness and mass.
class LinearisedSystem {
 public:
  /// mesh and sections as in the static analysis (sections' materials supply C*(w)); `points` from
  /// base_point_states on an assembler with the same mesh and sections; u_base full [mm].
  LinearisedSystem(const mesh::Mesh& mesh, const std::vector<Section>& sections, std::vector<PointBase> points,
                   Eigen::VectorXd u_base, AssemblyOptions options = {});
  ~LinearisedSystem();

  std::size_t num_dofs() const;  ///< 3 x nodes

  /// K*(w) on all DOFs [N/mm], w [rad/s] >= 0 (same pattern for every w). Thread-safe: concurrent
  /// callers (frequencies solved in parallel) evaluate C*(w) concurrently, the assembly one at a time.
  ComplexMatrix stiffness(double omega) const;
  /// K_R(0): real long-term tangent at the base state (material C*(0) = C_inf plus geometric) [N/mm].
  const SparseMatrix& long_term_stiffness() const { return K0_; }
  /// Consistent mass on all DOFs [t] (section densities).
  const SparseMatrix& mass() const { return M_; }
  /// Sections with a density <= 0 (a mass matrix needs all of them > 0).
  std::vector<std::string> sections_without_density() const;

  /// The base state, per element, as reference-volume averages over its quadrature points
  /// (elements without a section: zero stress, F = I), for output.
  struct ElementBase {
    std::vector<Mat3> cauchy;  ///< Cauchy stress of S_geo, J^-1 F S_geo F^T [MPa], current frame
    std::vector<Mat3> F;       ///< deformation gradient seen by the material [-]
  };
  ElementBase element_base() const;
  const Eigen::VectorXd& base_displacement() const;  ///< u_base [mm], 3 per node

  /// Complex amplitude of the linearised Cauchy stress perturbation per element [MPa] (reference-volume
  /// average over its points) for the harmonic displacement u_hat [mm] (first 3 x nodes entries used) at
  /// w [rad/s]: d sigma = J^-1 (dF S F^T + F S dF^T + F dS F^T) - sigma tr(F^-1 dF), dS = C*(w) : sym(F^T dF),
  /// F and S = S_geo of the base state, dF = d F / d u [u_hat] (the element kernel's F, so F-bar is
  /// included; exact for full elements, central difference for F-bar). docs/physics.md 4.
  std::vector<Mat3c> cauchy_perturbation(double omega, const Eigen::VectorXcd& u_hat) const;

 private:
  std::vector<Mat6c> point_tangents(double omega) const;  ///< C*(w) per quadrature point [MPa]
  SparseMatrix assemble_part(const std::vector<Mat6c>& C, bool imaginary) const;
  std::vector<PointOutput> point_outputs(const Eigen::VectorXd& u) const;  ///< kernel point outputs at u
  /// Reference-volume average per element of a per-point value (zero for elements without a section).
  template <class T, class Value>
  std::vector<T> element_average(const std::vector<PointOutput>& points, const Value& value) const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
  SparseMatrix K0_, M_;
};

}  // namespace cushion::solver::dynamics
