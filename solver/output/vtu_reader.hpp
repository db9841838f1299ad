#pragma once
/// Reading result files back with VTK's own XML reader (tests, post-processing, comparisons).
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "material/tensor.hpp"
#include "solver/output/frame_data.hpp"

namespace cushion::solver {

/// Everything a .vtu holds, as VTK reports it.
struct VtuContents {
  std::vector<Vec3> points;                       ///< [mm]
  std::vector<int> cell_types;                    ///< VTK cell type ids
  std::vector<std::vector<int>> cells;            ///< point ids in VTK order
  /// Per cell, per edge: point ids as VTK's cell class defines the edge (end, end[, mid-edge node]).
  std::vector<std::vector<std::vector<int>>> vtk_edges;
  std::map<std::string, NamedField> point_data, cell_data;
  std::optional<double> time;                     ///< "TimeValue" field data [s]
};

/// Reads a .vtu with vtkXMLUnstructuredGridReader; std::runtime_error if VTK cannot read it.
VtuContents read_vtu(const std::filesystem::path& file);

/// One <DataSet> of a .pvd collection.
struct PvdEntry {
  double time = 0.0;            ///< timestep attribute [s]
  std::filesystem::path file;   ///< as written (relative to the .pvd folder)
};

/// Parses a .pvd collection with vtkXMLDataParser; std::runtime_error if it is not a valid collection.
std::vector<PvdEntry> read_pvd(const std::filesystem::path& file);

}  // namespace cushion::solver
