#pragma once
/// Node-to-rigid-surface contact of a set of foam surface nodes against one moving rigid indenter.
///
/// Normal (augmented Lagrangian, Uzawa): per node a the contact force magnitude is
///   t_N = p(lambda_a - eps_a g_a)   [N],  eps_a = penalty [MPa/mm] x A_a (tributary area [mm^2]),
/// g_a = g(x_a - c(t)) the signed gap [mm], and the force on the node is t_N grad g. p is the ramp
/// <x> made C1 over a force width w = eps_a delta (delta = smoothing [mm]):
///   p(x) = 0 (x <= -w/2),  (x + w/2)^2 / (2 w) (|x| < w/2),  x (x >= w/2),
/// so a node carrying more than w/2 sees the exact augmented-Lagrangian law (the Uzawa fixed point
/// is g = 0, the flat-platen patch test stays exact) while the tangent is continuous across
/// contact opening/closing: no active-set cycling of semi-smooth Newton. The force is the gradient
/// of a potential, so the tangent eps p'(x) grad g grad g^T - t_N H is exact and symmetric. After
/// each converged Newton solve augment() sets lambda = t_N until the largest penetration is within
/// `tolerance` (Uzawa loop around Newton). With ContactParameters::augmented false (the linear
/// pressure-overclosure law of ABAQUS/CalculiX) lambda stays 0: t_N = p(-eps_a g_a), the pressure is
/// penalty x overclosure, and augment() accepts every converged solve.
/// Tangential (Coulomb, regularised): each contacting node has a stick point xi in the indenter
/// frame; trial force f_T = -eps_T P (x - c - xi), P = I - n n^T, n = grad g / |grad g|; if
/// |f_T| > mu t_N the node slips: f_T = mu t_N f_T / |f_T| and xi follows. The stick points are
/// the slip history, committed with the step state. Newly touching nodes start stuck at their
/// current point. The frictional tangent is unsymmetric (use an LU solver when mu > 0).
/// The active set (t_N > 0) follows the current iterate; switches per evaluation are counted
/// (last_switches()).
#include <memory>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"
#include "solver/assembler.hpp"
#include "solver/case/contact_spec.hpp"
#include "solver/contact/rigid_surface.hpp"
#include "solver/output/frame_data.hpp"

namespace cushion::solver {

/// Node status for output (frame array "<name>_status"; -1 there: node not in the contact set).
/// A closed node without friction slides freely: it is `slip`, never `stick`.
enum class ContactStatus { open = 0, stick = 1, slip = 2 };

/// Sums over the contact set at the last evaluation (indenter frame = reference axes).
struct ContactTotals {
  Vec3 force = Vec3::Zero();  ///< total force of the indenter on the foam [N]
  double normal_force = 0.0;  ///< sum of the normal force magnitudes t_N |grad g| [N]
  double area = 0.0;          ///< contact area (ContactSet::contact_area) [mm^2]
  double mean_pressure = 0.0; ///< normal_force / area [MPa] (0 without contact)
  double max_penetration = 0.0;  ///< largest -g over nodes carrying force [mm] (>= 0)
  double min_gap = 0.0;       ///< smallest g over the set [mm]
  int active = 0;             ///< nodes carrying normal force
  int slipping = 0;           ///< of which slipping (all of them without friction)
};

/// Outcome of one Uzawa update.
struct AugmentOutcome {
  bool converged = true;    ///< penetration within tolerance: no further solve needed
  bool failed = false;      ///< tolerance not reached within max_augmentations
  double max_penetration = 0.0;  ///< before the update [mm]
  std::string message;      ///< why failed (names the contact, the penalty and what to change)
};

class ContactSet {
 public:
  /// `nodes`: 0-based indices of the contact nodes; each must lie on an exterior face of `mesh`
  /// whose nodes all belong to the set (its tributary area must be > 0),
  /// otherwise cushion::InputError names the first such node by label. `mesh` must outlive this.
  ContactSet(std::string name, const mesh::Mesh& mesh, std::vector<int> nodes,
             std::shared_ptr<const RigidSurface> surface, ContactParameters parameters);

  /// Indenter translation c [mm] for the next evaluations (the end of the current increment).
  void set_position(const Vec3& c) { position_ = c; }
  const Vec3& position() const { return position_; }

  /// Adds the contact residual (minus the contact forces) to r_full [N] and, if K, the tangent on
  /// the free DOFs of `dofs` [N/mm] at full displacements u [mm]; stores the trial state.
  void evaluate(const Eigen::VectorXd& u, const DofMap& dofs, Eigen::VectorXd& r_full, SparseMatrix* K);
  /// The same at the indenter position `from` [mm] (the converged one of the previous increment),
  /// extrapolated linearly to position(): force F(x, from) - dF/dx (position() - from), tangent
  /// dF/dx at `from`. The increment predictor uses it so the contact nodes follow the indenter
  /// with the forces and curvature of a converged state, instead of seeing the full penetration
  /// of the new position at once (which inverts elements under steep indenter flanks).
  void evaluate_predictor(const Vec3& from, const Eigen::VectorXd& u, const DofMap& dofs, Eigen::VectorXd& r_full,
                          SparseMatrix* K);

  /// Checks the state of the last evaluation (a converged Newton solve): if the largest
  /// penetration exceeds the tolerance, lambda = t_N (another solve needed). Counts the updates
  /// of this increment; fails after max_augmentations.
  AugmentOutcome augment();
  /// Resets the augmentation count (start of an increment attempt).
  void begin_attempt() { augmentations_ = 0; }
  int augmentations() const { return augmentations_; }

  /// Accept the trial state (multipliers, stick points) of the last evaluation, or drop it.
  void commit();
  void revert();

  /// Totals of the last evaluation (or of the committed state after commit()).
  ContactTotals totals() const;
  /// Contact area of the last evaluation [mm^2]: the deformed foam surface (faces of the set with a
  /// closed node, current configuration) where it touches the indenter (gap <= `tolerance`, the band in
  /// which the contact counts as closed), projected on the indenter's surface: integral of
  /// |n_foam . n_indenter| dA, n_indenter =
  /// grad g / |grad g|, by 8 x 8 sample points per face (bilinear quads, subdivided triangles). Unlike the
  /// tributary areas of the closed nodes (which count whole the share of a node just outside the
  /// indenter's edge) it cannot exceed the indenter's surface: for a flat punch it is at most the
  /// footprint pi R^2 plus the tolerance band around its edge (2 pi R x tolerance).
  double contact_area() const;
  /// Largest penetration of the set at u [mm] (0 if none), and the node label where it occurs.
  std::pair<double, int> penetration_at(const Eigen::VectorXd& u) const;

  /// Per-node arrays of the last evaluation for a frame (size = mesh nodes; nodes not in the set:
  /// pressure 0, gap NaN, status -1): "<name>_pressure_kPa", "<name>_gap_mm", "<name>_status"
  /// (-1 not in the set, 0 open, 1 stick, 2 slip; ContactStatus), "<name>_force_N" (vector, force on the foam).
  void add_frame_fields(FrameData& frame) const;

  const std::string& name() const { return name_; }
  const std::vector<int>& nodes() const { return nodes_; }
  const std::vector<double>& areas() const { return area_; }  ///< tributary areas [mm^2]
  const RigidSurface& surface() const { return *surface_; }
  const ContactParameters& parameters() const { return p_; }
  /// Per-set-node values of the last evaluation (index k as in nodes()), read by the
  /// steady-state linearisation: normal force magnitudes t_N [N] (> 0: closed) and gaps g [mm].
  const std::vector<double>& normal_force_magnitudes() const { return t_N_; }
  const std::vector<double>& gaps() const { return gap_; }
  /// Active-set changes between the last two evaluations (for the log).
  int last_switches() const { return switches_; }

 private:
  /// evaluate() at indenter position c, extrapolated by dc [mm] (see evaluate_predictor).
  void evaluate_at(const Vec3& c, const Vec3& dc, const Eigen::VectorXd& u, const DofMap& dofs,
                   Eigen::VectorXd& r_full, SparseMatrix* K);

  std::string name_;
  const mesh::Mesh& mesh_;
  std::vector<int> nodes_;
  std::shared_ptr<const RigidSurface> surface_;
  ContactParameters p_;
  Vec3 position_ = Vec3::Zero();
  std::vector<double> area_;
  std::vector<std::vector<int>> faces_;  ///< corner nodes (indices k into nodes_) of the set's faces, in order
  // committed and trial per-node state
  std::vector<double> lambda_, lambda_trial_;
  std::vector<Vec3> xi_, xi_trial_;        ///< stick points in the indenter frame [mm]
  std::vector<char> touching_, touching_trial_;
  // last evaluation (output)
  std::vector<double> gap_, t_N_, grad_norm_;
  std::vector<Vec3> force_;
  std::vector<Vec3> y_;  ///< current node positions in the indenter frame [mm]
  std::vector<ContactStatus> status_;
  int augmentations_ = 0;
  int switches_ = 0;
};

/// Tributary areas [mm^2] of the given nodes: each exterior face whose nodes all belong to the set
/// (mesh::surface_from_node_set) gives an equal share of its reference area to each of its nodes
/// (the consistent nodal load of a uniform pressure on parallelograms and linear triangles; on the
/// quadratic faces of tet10 and hex20 a positive lumping over corner and mid-edge nodes, since the
/// consistent loads are zero or negative at the corners).
std::vector<double> tributary_areas(const mesh::Mesh& mesh, const std::vector<int>& nodes);

}  // namespace cushion::solver
