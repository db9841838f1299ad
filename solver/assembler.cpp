#include "solver/assembler.hpp"

#include <algorithm>
#include <array>
#include <barrier>
#include <exception>
#include <stdexcept>
#include <thread>

namespace cushion::solver {
namespace {

/// Greedy colouring: each element takes the smallest colour unused by the elements sharing a node.
std::vector<std::vector<int>> colour_elements(const mesh::Mesh& mesh, const std::vector<int>& active) {
  std::vector<std::vector<int>> node_elements(mesh.num_nodes());
  for (int e : active) {
    const auto& el = mesh.elements[e];
    for (int a = 0; a < mesh::nodes_per_element(el.type); ++a) node_elements[el.nodes[a]].push_back(e);
  }
  std::vector<int> colour(mesh.num_elements(), -1);
  std::vector<std::vector<int>> colours;
  std::vector<char> used;
  for (int e : active) {
    used.assign(colours.size() + 1, 0);
    const auto& el = mesh.elements[e];
    for (int a = 0; a < mesh::nodes_per_element(el.type); ++a)
      for (int other : node_elements[el.nodes[a]])
        if (colour[other] >= 0) used[colour[other]] = 1;
    const int c = static_cast<int>(std::find(used.begin(), used.end(), 0) - used.begin());
    if (c == static_cast<int>(colours.size())) colours.emplace_back();
    colour[e] = c;
    colours[c].push_back(e);
  }
  return colours;
}

/// The elements of `active` with a node owned by this process: those its rows need.
std::vector<int> local_elements(const mesh::Mesh& mesh, const std::vector<int>& active, const Distribution& d) {
  std::vector<int> local;
  for (int e : active) {
    const auto& el = mesh.elements[e];
    for (int a = 0; a < mesh::nodes_per_element(el.type); ++a)
      if (d.owns_node(el.nodes[a])) {
        local.push_back(e);
        break;
      }
  }
  return local;
}

/// Zeroes the entries of `full` (3 per node) at nodes this process does not own, then sums over the
/// processes: rows exact on their owner become whole everywhere.
void complete_rows(Eigen::VectorXd& full, const Distribution& d) {
  for (Eigen::Index i = 0; i < full.size(); ++i)
    if (!d.owns_node(static_cast<int>(i / 3))) full(i) = 0.0;
  d.sum(std::span<double>(full.data(), static_cast<std::size_t>(full.size())));
}

}  // namespace

Assembler::Assembler(const mesh::Mesh& mesh, std::vector<Section> sections, DofMap dofs, AssemblyOptions options)
    : mesh_(mesh), sections_(std::move(sections)), dofs_(std::move(dofs)), section_of_(mesh.num_elements(), -1) {
  if (dofs_.num_dofs() != 3 * mesh.num_nodes()) throw std::invalid_argument("Assembler: DofMap does not match the mesh");
  for (std::size_t s = 0; s < sections_.size(); ++s) {
    if (!sections_[s].material) throw std::invalid_argument("Assembler: section '" + sections_[s].name + "' has no material");
    for (int e : sections_[s].elements) {
      if (e < 0 || e >= static_cast<int>(mesh.num_elements()))
        throw std::invalid_argument("Assembler: section '" + sections_[s].name + "' names a missing element");
      if (section_of_[e] >= 0) throw std::invalid_argument("Assembler: element in two sections");
      if (sections_[s].formulation == Formulation::fbar && mesh.elements[e].type != mesh::ElementType::hex8)
        throw std::invalid_argument("Assembler: F-bar is available for hex8 elements only (section '" +
                                    sections_[s].name + "')");
      section_of_[e] = static_cast<int>(s);
    }
  }
  std::vector<int> active;
  point_offset_.assign(mesh.num_elements() + 1, 0);
  for (std::size_t e = 0; e < mesh.num_elements(); ++e) {
    const bool on = section_of_[e] >= 0;
    if (on) active.push_back(static_cast<int>(e));
    point_offset_[e + 1] = point_offset_[e] + (on ? num_points(mesh.elements[e].type) : 0);
  }
  distribution_ = options.distribution;
  colours_ = colour_elements(mesh, distribution_ ? local_elements(mesh, active, *distribution_) : active);

  num_threads_ = options.num_threads ? options.num_threads : std::max(1u, std::thread::hardware_concurrency());

  // Patterns: every (free row, free column) and (free row, constrained column) pair of every element.
  std::vector<Eigen::Triplet<double>> pairs, coupling;
  for (int e : active) {
    const auto& el = mesh.elements[e];
    const int n = mesh::nodes_per_element(el.type);
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) {
            const int r = dofs_.equation(DofMap::dof(el.nodes[a], i));
            const int c = dofs_.equation(DofMap::dof(el.nodes[b], j));
            if (r >= 0 && c >= 0) pairs.emplace_back(r, c, 0.0);
            const int k = dofs_.constrained_index(DofMap::dof(el.nodes[b], j));
            if (r >= 0 && k >= 0) coupling.emplace_back(r, k, 0.0);
          }
  }
  const auto nf = static_cast<Eigen::Index>(dofs_.num_free());
  pattern_.resize(nf, nf);
  pattern_.setFromTriplets(pairs.begin(), pairs.end());
  pattern_.makeCompressed();
  coupling_pattern_.resize(nf, static_cast<Eigen::Index>(dofs_.constrained_dofs().size()));
  coupling_pattern_.setFromTriplets(coupling.begin(), coupling.end());
  coupling_pattern_.makeCompressed();
}

SparseMatrix Assembler::make_matrix() const { return pattern_; }
SparseMatrix Assembler::make_coupling_matrix() const { return coupling_pattern_; }

StateStore Assembler::make_state_store() const {
  std::vector<StateStore::ElementLayout> layout(mesh_.num_elements());
  for (std::size_t e = 0; e < layout.size(); ++e)
    if (section_of_[e] >= 0)
      layout[e] = {num_points(mesh_.elements[e].type), sections_[section_of_[e]].material.get()};
  return StateStore(layout);
}

template <class Work>
void Assembler::for_each_element(const Work& work) const {
  std::size_t largest = 0;
  for (const auto& c : colours_) largest = std::max(largest, c.size());
  const unsigned T = static_cast<unsigned>(std::clamp<std::size_t>(largest, 1, num_threads_));
  std::vector<std::exception_ptr> errors(T);
  auto run = [&](unsigned t, std::barrier<>* sync) {
    for (const auto& colour : colours_) {
      const std::size_t begin = colour.size() * t / T, end = colour.size() * (t + 1) / T;
      for (std::size_t k = begin; k < end && !errors[t]; ++k) {
        try {
          work(colour[k], t);
        } catch (...) {
          errors[t] = std::current_exception();
        }
      }
      if (sync) sync->arrive_and_wait();
    }
  };
  if (T == 1) {
    run(0, nullptr);
  } else {
    std::barrier<> sync(T);
    std::vector<std::thread> threads;
    for (unsigned t = 1; t < T; ++t) threads.emplace_back(run, t, &sync);
    run(0, &sync);
    for (auto& th : threads) th.join();
  }
  for (const auto& err : errors)
    if (err) std::rethrow_exception(err);
}

NodeMatrix Assembler::gather(int e, const Eigen::VectorXd* u) const {
  const auto& el = mesh_.elements[e];
  const int n = mesh::nodes_per_element(el.type);
  NodeMatrix m(3, n);
  for (int a = 0; a < n; ++a) m.col(a) = u ? Vec3(u->segment<3>(3 * el.nodes[a])) : mesh_.nodes[el.nodes[a]];
  return m;
}

namespace {

/// Adds Ke(p, q) into A(row[p], col[q]) for every p, q with row[p] >= 0 and col[q] >= 0. The
/// element's rows are sorted once, so each column is a single forward walk through its entries.
void add_block(const ElementMatrix& Ke, const int* row, const int* col, int n, SparseMatrix& A) {
  int order[max_element_dofs];
  int m = 0;
  for (int p = 0; p < n; ++p)
    if (row[p] >= 0) order[m++] = p;
  std::sort(order, order + m, [row](int a, int b) { return row[a] < row[b]; });
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  double* values = A.valuePtr();
  for (int q = 0; q < n; ++q) {
    if (col[q] < 0) continue;
    int k = outer[col[q]];
    for (int i = 0; i < m; ++i) {
      const int p = order[i];
      while (inner[k] < row[p]) ++k;  // the pattern contains every (row, col) pair of the element
      values[k] += Ke(p, q);
    }
  }
}

}  // namespace

void Assembler::scatter(int e, const ElementMatrix& Ke, SparseMatrix* K, SparseMatrix* K_fc) const {
  const auto& el = mesh_.elements[e];
  const int n = 3 * mesh::nodes_per_element(el.type);
  int eq[max_element_dofs], fixed[max_element_dofs];
  for (int p = 0; p < n; ++p) {
    const int d = DofMap::dof(el.nodes[p / 3], p % 3);
    eq[p] = dofs_.equation(d);
    fixed[p] = dofs_.constrained_index(d);
  }
  if (K) add_block(Ke, eq, eq, n, *K);
  if (K_fc) add_block(Ke, eq, fixed, n, *K_fc);
}

AssemblyStatus Assembler::assemble(const Eigen::VectorXd& u_old, const Eigen::VectorXd& u_new, double dt,
                                   StateStore& state, Eigen::VectorXd& f_int, SparseMatrix* K,
                                   std::vector<PointOutput>* points, SparseMatrix* K_fc) const {
  if (K && (K->nonZeros() != pattern_.nonZeros() || K->rows() != pattern_.rows()))
    throw std::logic_error("Assembler::assemble: K does not have the assembler's pattern (use make_matrix)");
  if (K_fc && (K_fc->nonZeros() != coupling_pattern_.nonZeros() || K_fc->cols() != coupling_pattern_.cols()))
    throw std::logic_error("Assembler::assemble: K_fc does not have the coupling pattern (use make_coupling_matrix)");
  f_int.setZero(static_cast<Eigen::Index>(dofs_.num_dofs()));
  if (K) std::fill(K->valuePtr(), K->valuePtr() + K->nonZeros(), 0.0);
  if (K_fc) std::fill(K_fc->valuePtr(), K_fc->valuePtr() + K_fc->nonZeros(), 0.0);
  if (points) points->resize(num_points_total());

  std::vector<AssemblyStatus> per_thread(num_threads_);
  for_each_element([&](int e, unsigned t) {
    const Section& section = sections_[section_of_[e]];
    const auto& el = mesh_.elements[e];
    ElementInput in;
    in.type = el.type;
    in.formulation = section.formulation;
    in.X = gather(e, nullptr);
    in.u_old = gather(e, &u_old);
    in.u_new = gather(e, &u_new);
    in.material = section.material.get();
    in.state_old = state.old_state(e);
    in.state_new = state.new_state(e);
    in.dt = dt;
    std::span<PointOutput> out_points;
    if (points) out_points = std::span<PointOutput>(points->data() + point_offset_[e], num_points(el.type));
    const ElementOutput out = integrate_element(in, K || K_fc, out_points);

    AssemblyStatus& s = per_thread[t];
    s.dt_factor = std::min(s.dt_factor, out.dt_factor);
    const bool worse = static_cast<int>(out.status) > static_cast<int>(s.status);
    const bool same_earlier = out.status == s.status && out.status != material::Status::ok && e < s.element;
    if (worse || same_earlier) {
      s.status = out.status;
      s.element = e;
      s.point = out.failed_point;
      s.message = out.message;
    }
    for (int a = 0; a < mesh::nodes_per_element(el.type); ++a)
      f_int.segment<3>(3 * el.nodes[a]) += out.f_int.segment<3>(3 * a);
    if (K || K_fc) scatter(e, out.K, K, K_fc);
  });

  AssemblyStatus total;
  for (const auto& s : per_thread) {
    total.dt_factor = std::min(total.dt_factor, s.dt_factor);
    const bool worse = static_cast<int>(s.status) > static_cast<int>(total.status);
    if (worse || (s.status == total.status && s.status != material::Status::ok && s.element < total.element)) {
      total.status = s.status;
      total.element = s.element;
      total.point = s.point;
      total.message = s.message;
    }
  }
  if (!distribution_) return total;
  complete_rows(f_int, *distribution_);
  if (points) complete_points(*points, state);
  return agree(total);
}

AssemblyStatus Assembler::agree(const AssemblyStatus& local) const {
  const Distribution& d = *distribution_;
  AssemblyStatus all = local;
  all.dt_factor = d.min(local.dt_factor);
  all.status = static_cast<material::Status>(static_cast<int>(d.max(static_cast<int>(local.status))));
  if (all.status == material::Status::ok) return all;
  // The first element (in element order) of the worst status, and its message from its process.
  const double none = static_cast<double>(mesh_.num_elements());
  all.element = static_cast<int>(d.min(local.status == all.status ? local.element : none));
  const int root = static_cast<int>(d.min(local.status == all.status && local.element == all.element ? d.rank() : d.size()));
  all.point = static_cast<int>(d.max(d.rank() == root ? local.point : -1));
  all.message = d.broadcast(local.message, root);
  return all;
}

void Assembler::complete_points(std::vector<PointOutput>& points, StateStore& state) const {
  const Distribution& d = *distribution_;
  // Each element's points and trial state from its owner (the owner of its first node), zero elsewhere.
  auto fields = [](PointOutput& p) {
    return std::array<std::span<double>, 5>{std::span<double>(p.F.data(), 9), std::span<double>(p.S.data(), 6),
                                            std::span<double>(p.sigma.data(), 6), std::span<double>(p.X.data(), 3),
                                            std::span<double>(&p.dV0, 1)};
  };
  std::vector<double> packed;
  packed.reserve(25 * points.size());
  for (std::size_t e = 0; e < mesh_.num_elements(); ++e) {
    if (section_of_[e] < 0) continue;
    const bool mine = d.node_owner(mesh_.elements[e].nodes[0]) == d.rank();
    if (!mine) {
      const auto trial = state.new_state(static_cast<int>(e));
      std::fill(trial.begin(), trial.end(), 0.0);
    }
    for (std::size_t k = point_offset_[e]; k < point_offset_[e + 1]; ++k)
      for (std::span<double> f : fields(points[k])) {
        if (mine) packed.insert(packed.end(), f.begin(), f.end());
        else packed.insert(packed.end(), f.size(), 0.0);
      }
  }
  d.sum(packed);
  d.sum(state.trial_values());
  std::size_t j = 0;
  for (std::size_t e = 0; e < mesh_.num_elements(); ++e)
    if (section_of_[e] >= 0)
      for (std::size_t k = point_offset_[e]; k < point_offset_[e + 1]; ++k)
        for (std::span<double> f : fields(points[k])) {
          std::copy_n(packed.begin() + static_cast<std::ptrdiff_t>(j), f.size(), f.begin());
          j += f.size();
        }
}

void Assembler::complete_free(Eigen::VectorXd& v) const {
  if (!distribution_) return;
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (!distribution_->owns_node(dofs_.free_dofs()[i] / 3)) v(i) = 0.0;
  distribution_->sum(std::span<double>(v.data(), static_cast<std::size_t>(v.size())));
}

void Assembler::assemble_mass(SparseMatrix& M) const {
  if (M.nonZeros() != pattern_.nonZeros() || M.rows() != pattern_.rows())
    throw std::logic_error("Assembler::assemble_mass: M does not have the assembler's pattern (use make_matrix)");
  std::fill(M.valuePtr(), M.valuePtr() + M.nonZeros(), 0.0);
  for_each_element([&](int e, unsigned) {
    const double rho = sections_[section_of_[e]].density;
    if (rho != 0.0) scatter(e, consistent_mass(mesh_.elements[e].type, gather(e, nullptr), rho), &M, nullptr);
  });
  if (!distribution_) return;
  // Whole rows everywhere: zero the columns' entries in rows of nodes owned elsewhere, then sum.
  for (Eigen::Index k = 0; k < M.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(M, k); it; ++it)
      if (!distribution_->owns_node(dofs_.free_dofs()[it.row()] / 3)) it.valueRef() = 0.0;
  distribution_->sum(std::span<double>(M.valuePtr(), static_cast<std::size_t>(M.nonZeros())));
}

double Assembler::total_mass() const {
  double m = 0.0;
  for (std::size_t e = 0; e < mesh_.num_elements(); ++e)
    if (section_of_[e] >= 0)
      m += sections_[section_of_[e]].density * element_volume(mesh_.elements[e].type, gather(static_cast<int>(e), nullptr));
  return m;
}

}  // namespace cushion::solver
