#pragma once
/// Result files for ParaView: one VTK XML unstructured grid (.vtu, binary appended, zlib) per frame
/// and a .pvd collection listing the frames with their times. Every file is written to a temporary
/// name and renamed, and the .pvd is rewritten after every frame, so an interrupted run leaves
/// complete, openable files.
///
/// Arrays (units in the names): point data "displacement_mm", "reaction_force_N"; cell data
/// "cauchy_stress_kPa" (symmetric tensor XX YY ZZ XY YZ XZ, current frame), "von_mises_kPa",
/// "pressure_kPa" (-tr(sigma)/3), "log_strain" (Hencky ln V, same component order),
/// "principal_stretches" (descending), "J", "viscous_stress_norm_kPa", plus FrameData's extra fields.
/// Cell types: hex8 -> VTK_HEXAHEDRON, tet4 -> VTK_TETRA, tet10 -> VTK_QUADRATIC_TETRA; the node
/// orders of C3D8/C3D4/C3D10 and of these VTK cells agree (checked in tests/solver/test_output_vtu.cpp).
#include <filesystem>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"
#include "solver/output/frame_data.hpp"

namespace cushion::solver {

/// VTK cell type id of an element type (12 hexahedron, 10 tetra, 24 quadratic tetra).
int vtk_cell_type(mesh::ElementType type);

/// Writes one frame of `mesh` (reference coordinates, mm) as a .vtu file, atomically. Array sizes
/// must match the mesh (std::invalid_argument otherwise); std::runtime_error if the file cannot be written.
void write_vtu(const std::filesystem::path& file, const mesh::Mesh& mesh, const FrameData& frame);

/// A time series of frames: <folder>/<stem>_0000.vtu, ... and <folder>/<stem>.pvd.
class ResultSeries {
 public:
  /// Creates `folder`; removes the <stem>.pvd and <stem>_NNNN.vtu files of an earlier run there.
  explicit ResultSeries(std::filesystem::path folder, std::string stem = "results");

  /// Writes the frame's .vtu, then rewrites the .pvd with all frames so far; returns the .vtu path.
  std::filesystem::path write_frame(const mesh::Mesh& mesh, const FrameData& frame);

  std::filesystem::path pvd_file() const { return folder_ / (stem_ + ".pvd"); }
  std::size_t frame_count() const { return entries_.size(); }

 private:
  struct Entry {
    double time;       ///< [s]
    std::string file;  ///< relative to the folder
  };
  std::filesystem::path folder_;
  std::string stem_;
  std::vector<Entry> entries_;
};

}  // namespace cushion::solver
