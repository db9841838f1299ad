#include "solver/output/vtu_reader.hpp"

#include <cstdlib>
#include <stdexcept>

#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLUnstructuredGridReader.h>

namespace cushion::solver {

namespace {

std::map<std::string, NamedField> arrays(vtkFieldData* data) {
  std::map<std::string, NamedField> out;
  for (int k = 0; k < data->GetNumberOfArrays(); ++k) {
    vtkDataArray* a = data->GetArray(k);
    if (!a || !a->GetName()) continue;
    NamedField f;
    f.name = a->GetName();
    f.components = a->GetNumberOfComponents();
    f.values.resize(static_cast<std::size_t>(a->GetNumberOfTuples() * f.components));
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
      for (int c = 0; c < f.components; ++c) f.values[i * f.components + c] = a->GetComponent(i, c);
    out[f.name] = std::move(f);
  }
  return out;
}

}  // namespace

VtuContents read_vtu(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file)) throw std::runtime_error(file.string() + ": no such file");
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(file.string().c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  if (reader->GetErrorCode() != 0 || !grid || !grid->GetPoints())
    throw std::runtime_error(file.string() + ": VTK cannot read this .vtu file");

  VtuContents out;
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i) {
    double x[3];
    grid->GetPoint(i, x);
    out.points.emplace_back(x[0], x[1], x[2]);
  }
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c) {
    vtkCell* cell = grid->GetCell(c);
    out.cell_types.push_back(cell->GetCellType());
    std::vector<int> ids;
    for (vtkIdType k = 0; k < cell->GetNumberOfPoints(); ++k) ids.push_back(static_cast<int>(cell->GetPointId(k)));
    out.cells.push_back(std::move(ids));
    std::vector<std::vector<int>> edges;
    for (int e = 0; e < cell->GetNumberOfEdges(); ++e) {
      vtkCell* edge = cell->GetEdge(e);
      std::vector<int> edge_ids;
      for (vtkIdType k = 0; k < edge->GetNumberOfPoints(); ++k)
        edge_ids.push_back(static_cast<int>(edge->GetPointId(k)));
      edges.push_back(std::move(edge_ids));
    }
    out.vtk_edges.push_back(std::move(edges));
  }
  out.point_data = arrays(grid->GetPointData());
  out.cell_data = arrays(grid->GetCellData());
  auto field = arrays(grid->GetFieldData());
  if (auto it = field.find("TimeValue"); it != field.end() && !it->second.values.empty())
    out.time = it->second.values.front();
  return out;
}

std::vector<PvdEntry> read_pvd(const std::filesystem::path& file) {
  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName(file.string().c_str());
  if (!std::filesystem::is_regular_file(file) || parser->Parse() != 1)
    throw std::runtime_error(file.string() + ": not a readable XML file");
  vtkXMLDataElement* root = parser->GetRootElement();
  if (!root || std::string(root->GetName()) != "VTKFile" || !root->GetAttribute("type") ||
      std::string(root->GetAttribute("type")) != "Collection")
    throw std::runtime_error(file.string() + ": not a VTK collection (.pvd)");
  vtkXMLDataElement* collection = root->FindNestedElementWithName("Collection");
  if (!collection) throw std::runtime_error(file.string() + ": no <Collection> element");
  std::vector<PvdEntry> out;
  for (int k = 0; k < collection->GetNumberOfNestedElements(); ++k) {
    vtkXMLDataElement* e = collection->GetNestedElement(k);
    if (std::string(e->GetName()) != "DataSet") continue;
    const char* time = e->GetAttribute("timestep");
    const char* name = e->GetAttribute("file");
    if (!time || !name) throw std::runtime_error(file.string() + ": <DataSet> without timestep or file");
    out.push_back({std::strtod(time, nullptr), name});
  }
  return out;
}

}  // namespace cushion::solver
