#include "mesh/inp_reader.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <unordered_map>

#include "io/input_error.hpp"
#include "io/text_support.hpp"
#include "mesh/text.hpp"

namespace cushion::mesh {
namespace {


using Line = InpLine;
using Block = InpBlock;

[[noreturn]] void fail(const Line& line, const std::string& keyword, const std::string& what) {
  throw InputError(line.file + ":" + std::to_string(line.number) + ": " +
                   (keyword.empty() ? "" : "*" + keyword + ": ") + what);
}

}  // namespace

std::vector<std::string> inp_fields(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) out.push_back(trim(item));
  if (!out.empty() && out.back().empty()) out.pop_back();
  return out;
}

namespace {

bool ends_with_comma(const std::string& text) {
  const std::string t = trim(text);
  return !t.empty() && t.back() == ',';
}

// Reads a file into lines, expanding *INCLUDE, INPUT=... in place (paths relative to the includer).
void load(const std::string& text, const std::string& name, std::vector<Line>& lines, int depth) {
  if (depth > 20) throw InputError(name + ": *INCLUDE nested more than 20 levels");
  std::istringstream in(text);
  std::string raw;
  for (int number = 1; std::getline(in, raw); ++number) {
    const std::string t = trim(raw);
    if (t.empty() || t.rfind("**", 0) == 0) continue;
    const Line line{name, number, t};
    const std::vector<std::string> keyword_fields = t[0] == '*' ? inp_fields(t.substr(1)) : std::vector<std::string>{};
    if (!keyword_fields.empty() && io::upper_case(keyword_fields.front()) == "INCLUDE") {
      std::string input;
      for (const std::string& option : keyword_fields) {
        const auto eq = option.find('=');
        if (eq != std::string::npos && io::upper_case(trim(option.substr(0, eq))) == "INPUT")
          input = trim(option.substr(eq + 1));
      }
      if (input.size() >= 2 && input.front() == '"' && input.back() == '"')
        input = input.substr(1, input.size() - 2);
      if (input.empty()) fail(line, "INCLUDE", "missing INPUT=file");
      const std::filesystem::path path =
          std::filesystem::path(name).parent_path() / std::filesystem::path(input);
      // Only regular files: /dev/zero or a FIFO would be read for ever (found while writing the fuzz harness).
      std::error_code ec;
      if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
        fail(line, "INCLUDE", "'" + path.string() + "' is not a regular file");
      std::ifstream file(path);
      if (!file) fail(line, "INCLUDE", "cannot open '" + path.string() + "'");
      std::stringstream content;
      content << file.rdbuf();
      load(content.str(), path.string(), lines, depth + 1);
      continue;
    }
    lines.push_back(line);
  }
}

std::vector<Block> blocks(const std::vector<Line>& lines) {
  std::vector<Block> out;
  for (const Line& line : lines) {
    if (line.text[0] != '*') {
      if (out.empty()) fail(line, "", "data line before the first keyword");
      out.back().data.push_back(line);
      continue;
    }
    Block block;
    block.keyword = line;
    const std::vector<std::string> parts = inp_fields(line.text.substr(1));
    if (parts.empty() || parts[0].empty()) fail(line, "", "empty keyword");
    // Collapse inner blanks of multi-word keywords ("*End Step" -> "END STEP").
    std::istringstream words(io::upper_case(parts[0]));
    for (std::string w; words >> w;) block.name += (block.name.empty() ? "" : " ") + w;
    for (std::size_t i = 1; i < parts.size(); ++i) {
      const auto eq = parts[i].find('=');
      const std::string key = io::upper_case(trim(parts[i].substr(0, eq)));
      block.options[key] = eq == std::string::npos ? "" : trim(parts[i].substr(eq + 1));
    }
    out.push_back(std::move(block));
  }
  return out;
}

std::string read_deck_text(const std::string& path) {
  io::require_readable_file(path, ".inp file");
  std::ifstream file(path);
  if (!file) throw InputError(path + ": cannot open .inp file");
  std::stringstream content;
  content << file.rdbuf();
  return content.str();
}

class Reader {
 public:
  Reader(std::vector<std::string>* notes, bool report_skipped) : notes_(notes), report_skipped_(report_skipped) {}

  Mesh read(const std::vector<Block>& deck) {
    using Handler = void (Reader::*)(const Block&);
    static const std::map<std::string, Handler> handlers = {
        {"NODE", &Reader::node},  {"ELEMENT", &Reader::element}, {"NSET", &Reader::nset},
        {"ELSET", &Reader::elset}, {"SURFACE", &Reader::surface}};
    std::vector<const Block*> ignored;  // first block of each unused keyword, in deck order
    std::map<std::string, int> ignored_count;
    for (const Block& block : deck) {
      const auto it = handlers.find(block.name);
      if (it != handlers.end()) (this->*(it->second))(block);
      else if (ignored_count[block.name]++ == 0) ignored.push_back(&block);
    }
    if (notes_ && report_skipped_)
      for (const Block* block : ignored) notes_->push_back(ignored_note(*block, ignored_count[block->name]));
    for (auto* sets : {&mesh_.node_sets, &mesh_.element_sets})
      for (auto& [name, members] : *sets) {
        std::sort(members.begin(), members.end());
        members.erase(std::unique(members.begin(), members.end()), members.end());
      }
    return std::move(mesh_);
  }

 private:
  // "<file>:<line>: keyword *XYZ ignored (...)" for the first of `count` blocks of an unused keyword.
  static std::string ignored_note(const Block& block, int count) {
    return block.keyword.file + ":" + std::to_string(block.keyword.number) + ": keyword *" + block.name +
           " ignored (" + (count > 1 ? std::to_string(count) + " times, the first here; " : "") +
           "mesh import reads only *NODE, *ELEMENT, *NSET, *ELSET, *SURFACE, *INCLUDE)";
  }

  // --- field conversion -----------------------------------------------------------------------
  static int integer(const Line& line, const std::string& keyword, const std::string& text) {
    std::size_t used = 0;
    long value = 0;
    try {
      value = std::stol(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (text.empty() || used != text.size() || value < -2147483647L || value > 2147483647L)
      fail(line, keyword, "bad integer '" + text + "'");
    return static_cast<int>(value);
  }
  static double real(const Line& line, const std::string& keyword, const std::string& text) {
    const std::optional<double> value = io::parse_finite_number(text);
    if (!value) fail(line, keyword, "bad number '" + text + "'");
    return *value;
  }
  static std::string required(const Block& block, const std::string& option) {
    const auto it = block.options.find(option);
    if (it == block.options.end() || it->second.empty())
      fail(block.keyword, block.name, "missing " + option + "=");
    return it->second;
  }
  int node_index(const Line& line, const std::string& keyword, int label) const {
    const auto it = node_index_.find(label);
    if (it == node_index_.end()) fail(line, keyword, "undefined node label " + std::to_string(label));
    return it->second;
  }
  int element_index(const Line& line, const std::string& keyword, int label) const {
    const auto it = element_index_.find(label);
    if (it == element_index_.end())
      fail(line, keyword, "undefined element label " + std::to_string(label));
    return it->second;
  }
  template <class Sets>
  static std::string canonical(Sets& sets, const std::string& name) {
    const auto it = find_name(sets, name);
    return it == sets.end() ? name : it->first;
  }

  // --- keyword handlers -----------------------------------------------------------------------
  void node(const Block& block) {
    std::vector<int>* set = nullptr;
    if (block.options.count("NSET"))
      set = &mesh_.node_sets[canonical(mesh_.node_sets, required(block, "NSET"))];
    for (const Line& line : block.data) {
      const auto f = inp_fields(line.text);
      if (f.size() < 2 || f.size() > 4)
        fail(line, block.name, "expected 'label, x, y, z', got " + std::to_string(f.size()) + " fields");
      const int label = integer(line, block.name, f[0]);
      Vec3 x = Vec3::Zero();
      for (std::size_t d = 1; d < f.size(); ++d) x[d - 1] = real(line, block.name, f[d]);
      if (!node_index_.emplace(label, static_cast<int>(mesh_.nodes.size())).second)
        fail(line, block.name, "duplicate node label " + std::to_string(label));
      if (set) set->push_back(static_cast<int>(mesh_.nodes.size()));
      mesh_.nodes.push_back(x);
      mesh_.node_labels.push_back(label);
    }
  }

  void element(const Block& block) {
    static const std::map<std::string, ElementType> types = {
        {"C3D8", ElementType::hex8},   {"C3D8R", ElementType::hex8},    {"C3D4", ElementType::tet4},
        {"C3D10", ElementType::tet10}, {"C3D20", ElementType::hex20}, {"C3D20R", ElementType::hex20r}};
    const std::string type_name = io::upper_case(required(block, "TYPE"));
    const auto type = types.find(type_name);
    if (type == types.end())
      fail(block.keyword, block.name,
           "unknown TYPE=" + type_name + " (supported: C3D8, C3D8R, C3D4, C3D10, C3D20, C3D20R)");
    if (type_name == "C3D8R" && notes_)
      notes_->push_back(block.keyword.file + ":" + std::to_string(block.keyword.number) +
                        ": C3D8R read as C3D8 (hex8); the solver chooses the integration rule");
    std::vector<int>* set = nullptr;
    if (block.options.count("ELSET"))
      set = &mesh_.element_sets[canonical(mesh_.element_sets, required(block, "ELSET"))];
    const int n = nodes_per_element(type->second);
    std::vector<std::string> pending;
    const Line* first = nullptr;
    for (const Line& line : block.data) {
      if (!first) first = &line;
      const std::vector<std::string> line_fields = inp_fields(line.text);
      pending.insert(pending.end(), line_fields.begin(), line_fields.end());
      // ABAQUS continues an element on the next line when the line ends with a comma or is full
      // (16 entries: label and 15 nodes of a C3D20, as some writers omit the comma).
      const bool full_line = line_fields.size() == 16;
      if (static_cast<int>(pending.size()) < n + 1 && (ends_with_comma(line.text) || full_line)) continue;
      if (static_cast<int>(pending.size()) != n + 1)
        fail(line, block.name, type_name + " needs a label and " + std::to_string(n) +
                                   " nodes, got " + std::to_string(pending.size()) + " fields");
      Element element{type->second, {}, integer(*first, block.name, pending[0])};
      for (int a = 0; a < n; ++a)
        element.nodes[a] = node_index(line, block.name, integer(line, block.name, pending[a + 1]));
      if (!element_index_.emplace(element.label, static_cast<int>(mesh_.elements.size())).second)
        fail(*first, block.name, "duplicate element label " + std::to_string(element.label));
      if (set) set->push_back(static_cast<int>(mesh_.elements.size()));
      mesh_.elements.push_back(element);
      pending.clear();
      first = nullptr;
    }
    if (!pending.empty()) fail(*first, block.name, "incomplete element at end of block");
  }

  // Members of a *NSET / *ELSET block: labels, set names, or GENERATE ranges.
  template <class ToIndex, class Sets>
  void set_members(const Block& block, std::vector<int>& members, ToIndex to_index, Sets& sets) {
    const bool generate = block.options.count("GENERATE") > 0;
    for (const Line& line : block.data) {
      const auto f = inp_fields(line.text);
      if (generate) {
        if (f.size() < 2 || f.size() > 3)
          fail(line, block.name, "GENERATE expects 'first, last[, increment]'");
        // 64-bit range arithmetic: labels may span the whole int range (INT_MIN + 1 .. INT_MAX).
        const long long first = integer(line, block.name, f[0]), last = integer(line, block.name, f[1]);
        const long long step = f.size() == 3 ? integer(line, block.name, f[2]) : 1;
        if (step <= 0 || last < first || (last - first) % step != 0)
          fail(line, block.name, "bad GENERATE range " + std::to_string(first) + ", " +
                                     std::to_string(last) + ", " + std::to_string(step) +
                                     " (need first <= last, increment > 0 dividing last - first)");
        for (long long label = first; label <= last; label += step)
          members.push_back(to_index(line, static_cast<int>(label)));
        continue;
      }
      for (const std::string& item : f) {
        if (item.empty()) fail(line, block.name, "empty entry");
        if (std::isdigit(static_cast<unsigned char>(item[0])) || item[0] == '-') {
          members.push_back(to_index(line, integer(line, block.name, item)));
        } else {
          const auto it = find_name(sets, item);
          if (it == sets.end()) fail(line, block.name, "unknown set '" + item + "'");
          members.insert(members.end(), it->second.begin(), it->second.end());
        }
      }
    }
  }

  void nset(const Block& block) {
    const std::string name = canonical(mesh_.node_sets, required(block, "NSET"));
    std::vector<int> members;
    set_members(block, members,
                [&](const Line& line, int label) { return node_index(line, block.name, label); },
                mesh_.node_sets);
    if (block.options.count("ELSET")) {  // nodes of the elements of an element set
      const std::string elset = required(block, "ELSET");
      const auto it = find_name(mesh_.element_sets, elset);
      if (it == mesh_.element_sets.end()) fail(block.keyword, block.name, "unknown ELSET '" + elset + "'");
      for (int e : it->second)
        for (int a = 0; a < nodes_per_element(mesh_.elements[e].type); ++a)
          members.push_back(mesh_.elements[e].nodes[a]);
    }
    if (members.empty()) fail(block.keyword, block.name, "node set '" + name + "' is empty");
    auto& set = mesh_.node_sets[name];
    set.insert(set.end(), members.begin(), members.end());
  }

  void elset(const Block& block) {
    const std::string name = canonical(mesh_.element_sets, required(block, "ELSET"));
    std::vector<int> members;
    set_members(block, members,
                [&](const Line& line, int label) { return element_index(line, block.name, label); },
                mesh_.element_sets);
    if (members.empty()) fail(block.keyword, block.name, "element set '" + name + "' is empty");
    auto& set = mesh_.element_sets[name];
    set.insert(set.end(), members.begin(), members.end());
  }

  void surface(const Block& block) {
    const auto type = block.options.find("TYPE");
    if (type != block.options.end() && io::upper_case(type->second) != "ELEMENT")
      fail(block.keyword, block.name, "only TYPE=ELEMENT is supported, got TYPE=" + type->second);
    const std::string name = required(block, "NAME");
    std::vector<Face> faces;
    for (const Line& line : block.data) {
      const auto f = inp_fields(line.text);
      if (f.empty() || f.size() > 2) fail(line, block.name, "expected 'elset or element label, Sn'");
      std::vector<int> elements;
      if (std::isdigit(static_cast<unsigned char>(f[0][0]))) {
        elements.push_back(element_index(line, block.name, integer(line, block.name, f[0])));
      } else {
        const auto it = find_name(mesh_.element_sets, f[0]);
        if (it == mesh_.element_sets.end()) fail(line, block.name, "unknown element set '" + f[0] + "'");
        elements = it->second;
      }
      if (f.size() == 1) {  // no face identifier: all exterior faces of these elements
        std::vector<char> member(mesh_.elements.size(), 0);
        for (int e : elements) member[e] = 1;
        for (const Face& face : boundary_faces(mesh_))
          if (member[face.element]) faces.push_back(face);
        continue;
      }
      const std::string id = io::upper_case(f[1]);
      const int number = id.size() == 2 && id[0] == 'S' && std::isdigit(static_cast<unsigned char>(id[1]))
                             ? id[1] - '0' : 0;
      for (int e : elements) {
        const int count = faces_per_element(mesh_.elements[e].type);
        if (number < 1 || number > count)
          fail(line, block.name, "bad face '" + f[1] + "' for " + to_string(mesh_.elements[e].type) +
                                     " element " + std::to_string(mesh_.elements[e].label) +
                                     " (S1..S" + std::to_string(count) + ")");
        faces.push_back(Face{e, number - 1});
      }
    }
    if (faces.empty()) fail(block.keyword, block.name, "surface '" + name + "' is empty");
    auto& surface = mesh_.surfaces[name];
    surface.insert(surface.end(), faces.begin(), faces.end());
  }

  Mesh mesh_;
  std::unordered_map<int, int> node_index_, element_index_;
  std::vector<std::string>* notes_;
  bool report_skipped_ = true;
};

}  // namespace

std::vector<InpBlock> parse_inp_blocks(const std::string& text, const std::string& name) {
  std::vector<Line> lines;
  load(text, name, lines, 0);
  return blocks(lines);
}

std::vector<InpBlock> read_inp_blocks(const std::string& path) { return parse_inp_blocks(read_deck_text(path), path); }

Mesh mesh_from_inp_blocks(const std::vector<InpBlock>& deck, const std::string& name,
                          std::vector<std::string>* notes, bool report_skipped) {
  Mesh mesh = Reader(notes, report_skipped).read(deck);
  check_elements(mesh, name);
  return mesh;
}

Mesh parse_inp(const std::string& text, const std::string& name, std::vector<std::string>* notes) {
  return mesh_from_inp_blocks(parse_inp_blocks(text, name), name, notes, true);
}

Mesh read_inp(const std::string& path, std::vector<std::string>* notes) {
  return parse_inp(read_deck_text(path), path, notes);
}

}  // namespace cushion::mesh
