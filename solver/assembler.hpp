#pragma once
/// Global assembly: loops the element kernels over the mesh and scatters into the free-DOF system.
/// The sparsity pattern is built once (make_matrix); every assemble() refills its values without
/// reallocation. Elements are coloured (no two elements of a colour share a node) and each colour
/// is split between threads, so threads scatter without locks and every entry receives its
/// contributions in colour order: results are bitwise identical for any number of threads.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Sparse>

#include "mesh/mesh.hpp"
#include "solver/distribution.hpp"
#include "solver/dof_map.hpp"
#include "solver/elements/solid_element.hpp"
#include "solver/state_store.hpp"

namespace cushion::solver {

/// Column-major sparse matrix on the free DOFs (stiffness [N/mm], mass [t]).
using SparseMatrix = Eigen::SparseMatrix<double>;

/// A set of elements sharing a material and formulation (an ABAQUS *SOLID SECTION).
struct Section {
  std::string name;
  std::vector<int> elements;                            ///< 0-based element indices
  std::shared_ptr<const material::Material> material;  ///< shared, stateless, thread-safe
  Formulation formulation = Formulation::full;
  double density = 0.0;  ///< mass density [t/mm^3] (for the mass matrix)
};

/// Threading of the element loop.
struct AssemblyOptions {
  unsigned num_threads = 0;  ///< 0: std::thread::hardware_concurrency()
  /// A distributed run (distribution.hpp): evaluate only the elements touching this process's nodes
  /// and make the results whole (below). nullptr: one process, every element.
  std::shared_ptr<const Distribution> distribution;
};

/// Outcome of one global evaluation (worst element status; first failed element in element order).
struct AssemblyStatus {
  material::Status status = material::Status::ok;
  double dt_factor = 1.0;  ///< smallest proposal over all points
  int element = -1;        ///< first element (0-based) with a failed or unreliable point
  int point = -1;          ///< its quadrature point
  std::string message;
  /// True if a material point failed (results meaningless, cut back).
  bool failed() const { return status == material::Status::failed; }
};

/// Element loop, sparsity pattern and scatter for one mesh, its sections and its DOF map.
class Assembler {
 public:
  /// `mesh` must outlive the assembler. Each element may belong to at most one section; elements
  /// in no section are ignored. Throws std::invalid_argument on inconsistent input.
  Assembler(const mesh::Mesh& mesh, std::vector<Section> sections, DofMap dofs, AssemblyOptions options = {});

  /// A matrix with the free-DOF sparsity pattern (compressed) and zero values.
  SparseMatrix make_matrix() const;
  /// A matrix with the pattern of the coupling block K_fc (free rows x constrained columns, column k
  /// = dofs().constrained_dofs()[k]), zero values; used for the prescribed-displacement predictor.
  SparseMatrix make_coupling_matrix() const;
  /// State arrays for every element, initialised by the materials.
  StateStore make_state_store() const;

  /// Evaluates every element at u_new (full DOF vectors [mm], constrained values included) from the
  /// committed state in `state` over dt [s]. Writes f_int (full size [N]: at constrained DOFs it is
  /// the reaction), the free-free tangent into *K [N/mm] if K (must come from make_matrix()), the
  /// trial state, point outputs if `points` (resized to num_points_total()), and the coupling
  /// block d f_free / d u_constrained [N/mm] into *K_fc if K_fc (from make_coupling_matrix()).
  /// Distributed: f_int, the status, the point outputs and (when `points` is asked for) the trial
  /// state of every element are whole and equal on every process; K and K_fc are exact in the rows
  /// of the owned nodes only (what the linear solver takes; complete_free() for products with them).
  AssemblyStatus assemble(const Eigen::VectorXd& u_old, const Eigen::VectorXd& u_new, double dt, StateStore& state,
                          Eigen::VectorXd& f_int, SparseMatrix* K, std::vector<PointOutput>* points = nullptr,
                          SparseMatrix* K_fc = nullptr) const;

  /// Consistent mass matrix on the free DOFs [t] into M (from make_matrix()); whole on every process.
  void assemble_mass(SparseMatrix& M) const;
  /// A free-DOF vector exact in the rows of the owned nodes (e.g. K_fc du) made whole on every
  /// process (distributed runs; nothing to do on one process).
  void complete_free(Eigen::VectorXd& v) const;
  /// The distribution of a distributed run, nullptr on one process.
  const Distribution* distribution() const { return distribution_.get(); }

  /// Total mass sum rho V of all sections [t].
  double total_mass() const;

  /// Index of the first point output of element e (points of e are contiguous).
  std::size_t point_offset(int e) const { return point_offset_[e]; }
  /// Quadrature points of all active elements (size of the point-output vector).
  std::size_t num_points_total() const { return point_offset_.back(); }
  /// Section index of element e, -1 if none.
  int section_of(int e) const { return section_of_[e]; }

  const mesh::Mesh& mesh() const { return mesh_; }                    ///< the mesh (reference, mm)
  const DofMap& dofs() const { return dofs_; }                         ///< DOF numbering
  const std::vector<Section>& sections() const { return sections_; }  ///< sections as given
  unsigned num_threads() const { return num_threads_; }                ///< threads of the element loop
  std::size_t num_colours() const { return colours_.size(); }          ///< element colours

 private:
  template <class Work>
  void for_each_element(const Work& work) const;
  NodeMatrix gather(int e, const Eigen::VectorXd* u) const;
  void scatter(int e, const ElementMatrix& Ke, SparseMatrix* K, SparseMatrix* K_fc) const;
  AssemblyStatus agree(const AssemblyStatus& local) const;
  void complete_points(std::vector<PointOutput>& points, StateStore& state) const;

  std::shared_ptr<const Distribution> distribution_;

  const mesh::Mesh& mesh_;
  std::vector<Section> sections_;
  DofMap dofs_;
  unsigned num_threads_ = 1;
  std::vector<int> section_of_;
  std::vector<std::size_t> point_offset_;
  std::vector<std::vector<int>> colours_;  ///< element indices per colour, ascending
  SparseMatrix pattern_, coupling_pattern_;
};

}  // namespace cushion::solver
