#pragma once
/// ABAQUS/CalculiX .inp mesh input and output. Supported keywords: *NODE (NSET=), *ELEMENT
/// (TYPE=C3D8, C3D8R, C3D4, C3D10, C3D20, C3D20R; ELSET=; an element continues on the next line
/// after a line ending in a comma or holding 16 entries), *NSET / *ELSET (NSET= / ELSET=, GENERATE, members by
/// label or set name, *NSET with ELSET= taking the nodes of an element set), *SURFACE (TYPE=ELEMENT,
/// NAME=; lines "elset or label, Sn", Sn omitted = exterior faces of the set), *INCLUDE (INPUT=, path
/// relative to the including file). Other keywords (*HEADING, *MATERIAL, *STEP ...) are skipped,
/// each reported once (see read_inp). Coordinates are taken as mm. Node/element labels become
/// 0-based indices. A deck that also meshes other parts (an indenter): mesh::element_set_part.
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace cushion::mesh {

/// One line of a deck, after *INCLUDE expansion (comment and blank lines dropped).
struct InpLine {
  std::string file;  ///< the file it came from (for messages)
  int number = 0;    ///< 1-based line number in that file
  std::string text;  ///< trimmed
};

/// A keyword line with its data lines.
struct InpBlock {
  InpLine keyword;
  std::string name;                            ///< upper case, inner blanks collapsed, e.g. "END STEP"
  std::map<std::string, std::string> options;  ///< parameters: upper-case keys, values as written ("" if none)
  std::vector<InpLine> data;
};

/// The keyword blocks of a deck file, *INCLUDE expanded in place (InputError "file:line: ..." on a data
/// line before the first keyword, an empty keyword or a missing include).
std::vector<InpBlock> read_inp_blocks(const std::string& path);
std::vector<InpBlock> parse_inp_blocks(const std::string& text, const std::string& name);

/// Comma-separated fields of a line, trimmed; one trailing empty field (line ending in ',') dropped.
std::vector<std::string> inp_fields(const std::string& text);

/// The mesh of parsed blocks (as read_inp; `report_skipped` false: no notes about other keywords).
Mesh mesh_from_inp_blocks(const std::vector<InpBlock>& deck, const std::string& name,
                          std::vector<std::string>* notes, bool report_skipped);

/// Reads an .inp file. Errors throw cushion::InputError "file:line: *KEYWORD: message" (bad number,
/// unknown element TYPE, undefined or duplicate label, bad GENERATE, empty set, unknown set ...).
/// Warnings go to `notes` if given, one line each: reinterpreted element types, then every skipped
/// keyword once, in deck order, as "<file>:<line>: keyword *XYZ ignored (mesh import reads only *NODE,
/// ...)" with "N times, the first here; " inserted for a repeated keyword. The element Jacobians are
/// checked (check_elements).
Mesh read_inp(const std::string& path, std::vector<std::string>* notes = nullptr);

/// Same as read_inp for deck text in memory; `name` is used in messages and *INCLUDE paths are
/// relative to its directory.
Mesh parse_inp(const std::string& text, const std::string& name,
               std::vector<std::string>* notes = nullptr);

/// Writes nodes, elements (grouped by type), node sets, element sets and element surfaces with the
/// mesh's labels, full double precision, at most 16 entries per data line (a C3D20 element takes
/// two lines, the first ending in a comma).
void write_inp(const Mesh& mesh, std::ostream& out);
void write_inp(const Mesh& mesh, const std::string& path);

}  // namespace cushion::mesh
