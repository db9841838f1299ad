#include "solver/output/vtu_writer.hpp"

#include <cstdio>
#include <regex>
#include <sstream>
#include <stdexcept>

#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkCellData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include "io/text_support.hpp"
#include "solver/output/cell_measures.hpp"

namespace cushion::solver {

namespace {

constexpr double kPa_per_MPa = 1000.0;
const char* kTensorComponents[6] = {"XX", "YY", "ZZ", "XY", "YZ", "XZ"};

vtkSmartPointer<vtkDoubleArray> make_array(const std::string& name, int components, std::size_t tuples) {
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name.c_str());
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(static_cast<vtkIdType>(tuples));
  if (components == 6)
    for (int c = 0; c < 6; ++c) a->SetComponentName(c, kTensorComponents[c]);
  return a;
}

void require_size(std::size_t actual, std::size_t expected, const std::string& what) {
  if (actual != expected)
    throw std::invalid_argument("write_vtu: " + what + " has " + std::to_string(actual) + " entries, expected " +
                                std::to_string(expected));
}

vtkSmartPointer<vtkDoubleArray> vector_array(const std::string& name, const std::vector<Vec3>& v, double scale) {
  auto a = make_array(name, 3, v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int c = 0; c < 3; ++c) a->SetComponent(static_cast<vtkIdType>(i), c, scale * v[i](c));
  return a;
}

/// Symmetric tensors as 6 components XX YY ZZ XY YZ XZ (the Voigt stress order of tensor.hpp).
vtkSmartPointer<vtkDoubleArray> tensor_array(const std::string& name, const std::vector<Mat3>& t, double scale) {
  auto a = make_array(name, 6, t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Vec6 v = to_voigt_stress(0.5 * (t[i] + t[i].transpose()));
    for (int c = 0; c < 6; ++c) a->SetComponent(static_cast<vtkIdType>(i), c, scale * v(c));
  }
  return a;
}

template <class F>
vtkSmartPointer<vtkDoubleArray> scalar_array(const std::string& name, std::size_t n, F value) {
  auto a = make_array(name, 1, n);
  for (std::size_t i = 0; i < n; ++i) a->SetValue(static_cast<vtkIdType>(i), value(i));
  return a;
}

vtkSmartPointer<vtkDoubleArray> named_array(const NamedField& field, std::size_t n) {
  if (field.components < 1) throw std::invalid_argument("write_vtu: field " + field.name + ": components < 1");
  require_size(field.values.size(), n * static_cast<std::size_t>(field.components), "field " + field.name);
  auto a = make_array(field.name, field.components, n);
  for (std::size_t k = 0; k < field.values.size(); ++k) a->SetValue(static_cast<vtkIdType>(k), field.values[k]);
  return a;
}

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace

int vtk_cell_type(mesh::ElementType type) {
  switch (type) {
    case mesh::ElementType::hex8: return VTK_HEXAHEDRON;
    case mesh::ElementType::tet4: return VTK_TETRA;
    case mesh::ElementType::tet10: return VTK_QUADRATIC_TETRA;
    case mesh::ElementType::hex20:
    case mesh::ElementType::hex20r: return VTK_QUADRATIC_HEXAHEDRON;
  }
  throw std::logic_error("vtk_cell_type: unknown element type");
}

void write_vtu(const std::filesystem::path& file, const mesh::Mesh& mesh, const FrameData& frame) {
  const std::size_t nn = mesh.num_nodes(), ne = mesh.num_elements();
  require_size(frame.displacement.size(), nn, "displacement");
  auto optional_size = [](std::size_t actual, std::size_t expected, const std::string& what) {
    if (actual != 0) require_size(actual, expected, what);
  };
  optional_size(frame.reaction_force.size(), nn, "reaction_force");
  optional_size(frame.cauchy_stress.size(), ne, "cauchy_stress");
  optional_size(frame.deformation_gradient.size(), ne, "deformation_gradient");
  optional_size(frame.viscous_stress_norm.size(), ne, "viscous_stress_norm");

  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(nn));
  for (std::size_t i = 0; i < nn; ++i)
    points->SetPoint(static_cast<vtkIdType>(i), mesh.nodes[i](0), mesh.nodes[i](1), mesh.nodes[i](2));
  grid->SetPoints(points);
  grid->Allocate(static_cast<vtkIdType>(ne));
  for (const mesh::Element& e : mesh.elements) {
    // C3D8, C3D4, C3D10 and C3D20(R) node orders are those of VTK's hexahedron, tetra, quadratic
    // tetra and quadratic hexahedron (mid-edge nodes on (0,1), (1,2), (2,3), (3,0), (4,5), (5,6),
    // (6,7), (7,4), (0,4), (1,5), (2,6), (3,7): vtkQuadraticHexahedron.h).
    const int n = mesh::nodes_per_element(e.type);
    vtkIdType ids[20];
    for (int a = 0; a < n; ++a) ids[a] = e.nodes[a];
    grid->InsertNextCell(vtk_cell_type(e.type), n, ids);
  }

  vtkPointData* pd = grid->GetPointData();
  pd->AddArray(vector_array("displacement_mm", frame.displacement, 1.0));
  pd->SetActiveVectors("displacement_mm");
  if (!frame.reaction_force.empty()) pd->AddArray(vector_array("reaction_force_N", frame.reaction_force, 1.0));
  for (const NamedField& f : frame.point_fields) pd->AddArray(named_array(f, nn));

  vtkCellData* cd = grid->GetCellData();
  if (!frame.cauchy_stress.empty()) {
    const auto& sigma = frame.cauchy_stress;
    cd->AddArray(tensor_array("cauchy_stress_kPa", sigma, kPa_per_MPa));
    cd->AddArray(scalar_array("von_mises_kPa", ne, [&](std::size_t i) { return kPa_per_MPa * von_mises(sigma[i]); }));
    cd->AddArray(scalar_array("pressure_kPa", ne, [&](std::size_t i) { return kPa_per_MPa * pressure(sigma[i]); }));
  }
  if (!frame.deformation_gradient.empty()) {
    const auto& F = frame.deformation_gradient;
    std::vector<Mat3> strain(ne);
    std::vector<Vec3> stretches(ne);
    for (std::size_t i = 0; i < ne; ++i) {
      strain[i] = log_strain(F[i]);
      stretches[i] = principal_stretches(F[i]);
    }
    cd->AddArray(tensor_array("log_strain", strain, 1.0));
    cd->AddArray(vector_array("principal_stretches", stretches, 1.0));
    cd->AddArray(scalar_array("J", ne, [&](std::size_t i) { return F[i].determinant(); }));
  }
  if (!frame.viscous_stress_norm.empty())
    cd->AddArray(scalar_array("viscous_stress_norm_kPa", ne,
                              [&](std::size_t i) { return kPa_per_MPa * frame.viscous_stress_norm[i]; }));
  for (const NamedField& f : frame.cell_fields) cd->AddArray(named_array(f, ne));

  auto time = make_array("TimeValue", 1, 1);  // the field-data name ParaView reads as the time
  time->SetValue(0, frame.time);
  grid->GetFieldData()->AddArray(time);

  std::filesystem::create_directories(file.parent_path().empty() ? "." : file.parent_path());
  const std::filesystem::path temporary = file.string() + ".tmp";
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetInputData(grid);
  writer->SetFileName(temporary.string().c_str());
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw binary
  writer->SetHeaderTypeToUInt64();
  writer->SetCompressorTypeToZLib();
  if (writer->Write() != 1 || writer->GetErrorCode() != 0) {
    std::filesystem::remove(temporary);
    throw std::runtime_error(file.string() + ": cannot write the result file");
  }
  std::filesystem::rename(temporary, file);
}

ResultSeries::ResultSeries(std::filesystem::path folder, std::string stem)
    : folder_(std::move(folder)), stem_(std::move(stem)) {
  std::filesystem::create_directories(folder_);
  const std::regex old_frame(std::regex_replace(stem_, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") +
                             R"(_\d+\.vtu)");
  for (const auto& entry : std::filesystem::directory_iterator(folder_)) {
    const std::string name = entry.path().filename().string();
    if (name == stem_ + ".pvd" || std::regex_match(name, old_frame)) std::filesystem::remove(entry.path());
  }
}

std::filesystem::path ResultSeries::write_frame(const mesh::Mesh& mesh, const FrameData& frame) {
  char number[32];
  std::snprintf(number, sizeof number, "_%04zu.vtu", entries_.size());
  const std::string name = stem_ + number;
  write_vtu(folder_ / name, mesh, frame);
  entries_.push_back({frame.time, name});

  std::ostringstream pvd;
  pvd << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
  for (const Entry& e : entries_)
    pvd << "    <DataSet timestep=\"" << io::format_double(e.time) << "\" group=\"\" part=\"0\" file=\""
        << xml_escape(e.file) << "\"/>\n";
  pvd << "  </Collection>\n</VTKFile>\n";
  io::write_file_atomically(pvd_file(), pvd.str());
  return folder_ / name;
}

}  // namespace cushion::solver
