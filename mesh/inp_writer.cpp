#include <fstream>
#include <ostream>

#include "io/input_error.hpp"
#include "mesh/inp_reader.hpp"

namespace cushion::mesh {
namespace {

// Writes labels 16 per line, comma separated; `continued`: a broken line ends in a comma (one
// record over several lines, as an element's label and nodes).
void write_labels(std::ostream& out, const std::vector<int>& labels, bool continued = false) {
  for (std::size_t i = 0; i < labels.size(); ++i)
    out << labels[i] << (i + 1 == labels.size() ? "\n" : i % 16 == 15 ? (continued ? ",\n" : "\n") : ", ");
}

}  // namespace

void write_inp(const Mesh& mesh, std::ostream& out) {
  out.precision(17);
  out << "** written by cushion: lengths in mm\n*NODE\n";
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i)
    out << mesh.node_labels[i] << ", " << mesh.nodes[i].x() << ", " << mesh.nodes[i].y() << ", "
        << mesh.nodes[i].z() << "\n";
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    const Element& element = mesh.elements[e];
    if (e == 0 || mesh.elements[e - 1].type != element.type)
      out << "*ELEMENT, TYPE=" << to_string(element.type) << "\n";
    std::vector<int> record{element.label};
    for (int a = 0; a < nodes_per_element(element.type); ++a) record.push_back(mesh.node_labels[element.nodes[a]]);
    write_labels(out, record, true);
  }
  for (const auto& [name, nodes] : mesh.node_sets) {
    if (nodes.empty()) continue;  // ABAQUS rejects empty sets
    out << "*NSET, NSET=" << name << "\n";
    std::vector<int> labels;
    for (int n : nodes) labels.push_back(mesh.node_labels[n]);
    write_labels(out, labels);
  }
  for (const auto& [name, elements] : mesh.element_sets) {
    if (elements.empty()) continue;
    out << "*ELSET, ELSET=" << name << "\n";
    std::vector<int> labels;
    for (int e : elements) labels.push_back(mesh.elements[e].label);
    write_labels(out, labels);
  }
  for (const auto& [name, faces] : mesh.surfaces) {
    if (faces.empty()) continue;
    out << "*SURFACE, TYPE=ELEMENT, NAME=" << name << "\n";
    for (const Face& face : faces) out << mesh.elements[face.element].label << ", S" << face.face + 1 << "\n";
  }
}

void write_inp(const Mesh& mesh, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot write .inp file");
  write_inp(mesh, out);
}

}  // namespace cushion::mesh
