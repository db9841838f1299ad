#include "solver/petsc/mpi_distribution.hpp"

#include <metis.h>
#include <petscsys.h>

#include <algorithm>
#include <stdexcept>

namespace cushion::solver::petsc {

namespace {

/// Throws std::runtime_error("MPI: <call> failed") unless `code` is MPI_SUCCESS.
void check_mpi(int code, const char* call) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + call + " failed");
}

class MpiDistribution final : public Distribution {
 public:
  MpiDistribution(std::vector<int> owners, int rank, int size)
      : Distribution(std::move(owners)), rank_(rank), size_(size) {}
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  void sum(std::span<double> values) const override {
    check_mpi(MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_SUM,
                            PETSC_COMM_WORLD),
              "MPI_Allreduce");
  }
  double max(double value) const override { return reduce(value, MPI_MAX); }
  double min(double value) const override { return reduce(value, MPI_MIN); }
  std::string broadcast(const std::string& text, int root) const override {
    int length = static_cast<int>(text.size());
    check_mpi(MPI_Bcast(&length, 1, MPI_INT, root, PETSC_COMM_WORLD), "MPI_Bcast");
    std::string out = rank_ == root ? text : std::string(static_cast<std::size_t>(length), ' ');
    check_mpi(MPI_Bcast(out.data(), length, MPI_CHAR, root, PETSC_COMM_WORLD), "MPI_Bcast");
    return out;
  }
  void broadcast(std::span<double> values, int root) const override {
    check_mpi(MPI_Bcast(values.data(), static_cast<int>(values.size()), MPI_DOUBLE, root, PETSC_COMM_WORLD),
              "MPI_Bcast");
  }

 private:
  double reduce(double value, MPI_Op op) const {
    check_mpi(MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, op, PETSC_COMM_WORLD), "MPI_Allreduce");
    return value;
  }
  int rank_, size_;
};

}  // namespace

int world_size() {
  int size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return size;
}

int world_rank() {
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  return rank;
}

std::vector<int> partition_nodes(const mesh::Mesh& mesh, int parts) {
  const std::size_t n = mesh.num_nodes();
  // Graph of nodes sharing an element (CSR, no self loops).
  std::vector<std::vector<idx_t>> neighbours(n);
  for (const auto& el : mesh.elements) {
    const int m = mesh::nodes_per_element(el.type);
    for (int a = 0; a < m; ++a)
      for (int b = 0; b < m; ++b)
        if (a != b) neighbours[el.nodes[a]].push_back(el.nodes[b]);
  }
  std::vector<idx_t> xadj{0}, adjncy;
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    adjncy.insert(adjncy.end(), list.begin(), list.end());
    xadj.push_back(static_cast<idx_t>(adjncy.size()));
    std::vector<idx_t>().swap(list);
  }
  idx_t vertices = static_cast<idx_t>(n), constraints = 1, count = parts, cut = 0;
  std::vector<idx_t> part(n, 0);
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 1;  // the same partition on every run
  if (n > static_cast<std::size_t>(parts)) {
    const int status = METIS_PartGraphKway(&vertices, &constraints, xadj.data(), adjncy.data(), nullptr, nullptr,
                                           nullptr, &count, nullptr, nullptr, options, &cut, part.data());
    if (status != METIS_OK) throw std::runtime_error("METIS could not partition the mesh (status " + std::to_string(status) + ")");
  } else {
    for (std::size_t i = 0; i < n; ++i) part[i] = static_cast<idx_t>(i % static_cast<std::size_t>(parts));
  }
  std::vector<int> owner(part.begin(), part.end());
  // Nodes in no element (reference nodes of rigid bodies) to process 0.
  for (std::size_t i = 0; i < n; ++i)
    if (xadj[i + 1] == xadj[i]) owner[i] = 0;
  return owner;
}

std::shared_ptr<const Distribution> make_distribution(const mesh::Mesh& mesh) {
  const int size = world_size(), rank = world_rank();
  std::vector<int> owner(mesh.num_nodes(), 0);
  int failed = 0;
  if (rank == 0) {
    try {
      owner = partition_nodes(mesh, size);
    } catch (const std::runtime_error&) {
      failed = 1;
    }
  }
  check_mpi(MPI_Bcast(&failed, 1, MPI_INT, 0, PETSC_COMM_WORLD), "MPI_Bcast");
  if (failed) throw std::runtime_error("METIS could not partition the mesh over " + std::to_string(size) + " processes");
  check_mpi(MPI_Bcast(owner.data(), static_cast<int>(owner.size()), MPI_INT, 0, PETSC_COMM_WORLD), "MPI_Bcast");
  return std::make_shared<MpiDistribution>(std::move(owner), rank, size);
}

}  // namespace cushion::solver::petsc
