#pragma once
/// A run spread over several processes (MPI ranks) with the model replicated on each: every process
/// holds the whole mesh, DOF map and state vectors, but evaluates only the elements that touch the
/// nodes it OWNS (a partition of the nodes), so the rows of those nodes are exact on it and the
/// other rows partial. The reductions here make vectors, matrices and point data whole again on
/// every process, so every decision taken from them (convergence, cut-back, contact status) is the
/// same everywhere without further messages. The linear solver receives only the owned rows.
///
/// This interface knows no MPI: solver/petsc/ implements it (docs/parallel.md has the design).
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace cushion::solver {

/// The partition of the nodes over the processes and the collective operations on replicated data.
/// Every method is collective: all processes call it in the same order with arguments of the same size.
class Distribution {
 public:
  virtual ~Distribution() = default;

  virtual int rank() const = 0;  ///< this process, 0 .. size() - 1
  virtual int size() const = 0;  ///< number of processes (>= 2 for a distributed run)

  /// Process owning node n (its three rows, and the elements whose first node it is).
  int node_owner(int n) const { return node_owner_[n]; }
  bool owns_node(int n) const { return node_owner_[n] == rank(); }
  /// Node owners, one per mesh node.
  const std::vector<int>& node_owners() const { return node_owner_; }

  /// In-place sum of `values` over the processes (every process gets the sum).
  virtual void sum(std::span<double> values) const = 0;
  /// Largest / smallest value over the processes.
  virtual double max(double value) const = 0;
  virtual double min(double value) const = 0;
  /// The bytes of `text` on process `root`, everywhere.
  virtual std::string broadcast(const std::string& text, int root) const = 0;
  /// `values` of process `root`, everywhere (same size on every process).
  virtual void broadcast(std::span<double> values, int root) const = 0;

 protected:
  /// `owners`: the owning process of every node.
  explicit Distribution(std::vector<int> owners) : node_owner_(std::move(owners)) {}

 private:
  std::vector<int> node_owner_;
};

}  // namespace cushion::solver
