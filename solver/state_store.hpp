#pragma once
/// Internal-state arrays of every quadrature point, owned by the solver (not the materials): a
/// committed buffer (`old`, read by every evaluation) and a trial buffer (`new`, written by every
/// evaluation). commit() accepts the trial state after a converged increment, revert() drops it.
#include <span>
#include <vector>

#include "material/material.hpp"

namespace cushion::solver {

/// Old/new internal-state buffers of every quadrature point of every element.
class StateStore {
 public:
  /// Layout of one element: number of quadrature points and its material (state_size doubles per point).
  struct ElementLayout {
    int num_points = 0;
    const material::Material* material = nullptr;
  };

  /// Empty store (no elements).
  StateStore() = default;
  /// Allocates and fills both buffers with each material's initial_state().
  explicit StateStore(const std::vector<ElementLayout>& layout);

  /// Committed state of element e (points x state_size doubles).
  std::span<const double> old_state(int e) const { return {old_.data() + offset_[e], offset_[e + 1] - offset_[e]}; }
  /// Trial state of element e, written by an evaluation.
  std::span<double> new_state(int e) { return {new_.data() + offset_[e], offset_[e + 1] - offset_[e]}; }
  /// Trial state of element e, read only.
  std::span<const double> new_state(int e) const { return {new_.data() + offset_[e], offset_[e + 1] - offset_[e]}; }

  /// Every trial value, element after element (for the reductions of a distributed run).
  std::span<double> trial_values() { return new_; }

  void commit() { old_ = new_; }  ///< trial state becomes the committed state
  void revert() { new_ = old_; }  ///< trial state reset to the committed state

  /// Elements covered (including those without state).
  std::size_t num_elements() const { return offset_.empty() ? 0 : offset_.size() - 1; }
  std::size_t size() const { return old_.size(); }  ///< doubles per buffer

 private:
  std::vector<std::size_t> offset_;
  std::vector<double> old_, new_;
};

}  // namespace cushion::solver
