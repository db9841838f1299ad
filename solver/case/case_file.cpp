// The top level of the case grammar (case_spec.hpp): the root object, "solver", and JSON reading.
// Its parts: parse_mesh.cpp, parse_named.cpp (sets, amplitudes), parse_step.cpp, parse_contact.cpp,
// parse_dynamic.cpp (damping, newmark), parse_steady_state.cpp; checks against the built mesh and
// material: case_check.cpp.
#include "solver/case/case_file.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>

#include "io/input_error.hpp"
#include "io/json_reader.hpp"
#include "solver/case/case_parts.hpp"

namespace cushion::solver {

namespace case_parse {

namespace {

/// Why `options` is not a PETSc option string ("-name [value] -name [value] ..."), or "" if it is.
/// Option names start with '-' and a letter; each takes at most one value (a negative number is a value).
std::string petsc_options_syntax_problem(const std::string& options) {
  std::istringstream words(options);
  bool after_name = false;
  for (std::string w; words >> w;) {
    const bool name = w.size() > 1 && w[0] == '-' && std::isalpha(static_cast<unsigned char>(w[1]));
    if (!name && !after_name)
      return "'" + w + "' is not an option name (PETSc options look like \"-ksp_type cg -pc_type gamg\")";
    after_name = name;
  }
  return {};
}

}  // namespace

SolverSpec parse_solver(const Obj& o) {
  SolverSpec s;
  if (o.has("threads")) s.threads = o.integer("threads", 0, 1024);
  const std::string ls = o.choice_or("linear_solver", {"auto", "cholmod", "umfpack", "petsc"}, "auto");
  s.linear_solver = ls == "cholmod"   ? SolverSpec::LinearSolver::cholmod
                    : ls == "umfpack" ? SolverSpec::LinearSolver::umfpack
                    : ls == "petsc"   ? SolverSpec::LinearSolver::petsc
                                      : SolverSpec::LinearSolver::automatic;
  if (o.has("petsc_options")) {
    if (s.linear_solver != SolverSpec::LinearSolver::petsc)
      o.fail("petsc_options", "applies only with \"linear_solver\": \"petsc\"");
    s.petsc_options = o.string("petsc_options");
    const std::string problem = petsc_options_syntax_problem(s.petsc_options);
    if (!problem.empty()) o.fail("petsc_options", problem);
  }
  s.residual_tolerance = o.positive_or("residual_tolerance", s.residual_tolerance);
  s.correction_tolerance = o.positive_or("correction_tolerance", s.correction_tolerance);
  if (o.has("max_iterations")) s.max_iterations = o.integer("max_iterations", 1, 1000);
  if (o.has("max_cutbacks")) s.max_cutbacks = o.integer("max_cutbacks", 0, 100);
  s.cutback_factor = o.positive_or("cutback_factor", s.cutback_factor);
  if (s.cutback_factor >= 1.0) o.fail("cutback_factor", "must be < 1");
  s.growth_factor = o.positive_or("growth_factor", s.growth_factor);
  if (s.growth_factor < 1.0) o.fail("growth_factor", "must be >= 1");
  s.tangent_reuse = o.choice_or("newton", {"full", "modified"}, "full") == "modified";
  s.max_contraction = o.positive_or("max_contraction", s.max_contraction);
  if (s.max_contraction >= 1.0) o.fail("max_contraction", "must be < 1");
  return s;
}

}  // namespace case_parse

namespace {

using nlohmann::json;
using case_parse::Obj;

/// io::parse_json, plus numbers too large for a double (nlohmann out_of_range 406, which
/// io::parse_json does not catch) reported as InputError with line and the key before them.
json parse_json_finite(const std::string& text, const std::string& source) {
  try {
    return io::parse_json(text, source);
  } catch (const json::out_of_range& e) {
    const std::string what = e.what();
    const auto open = what.find('\''), close = what.rfind('\'');
    const std::string token = open < close ? what.substr(open + 1, close - open - 1) : std::string{};
    const std::size_t at = token.empty() ? std::string::npos : text.find(token);
    std::string where;
    if (at != std::string::npos) {
      const std::string head = text.substr(0, at);
      where = ":" + std::to_string(1 + std::count(head.begin(), head.end(), '\n'));
      const auto colon = head.rfind(':');
      const auto key_end = colon == std::string::npos ? std::string::npos : head.rfind('"', colon);
      const auto key_begin =
          key_end == std::string::npos || key_end == 0 ? std::string::npos : head.rfind('"', key_end - 1);
      if (key_begin != std::string::npos)
        where += ": key '" + head.substr(key_begin + 1, key_end - key_begin - 1) + "'";
    }
    throw InputError(source + where + ": invalid JSON: number '" + token +
                     "' is out of range (numbers must be finite)");
  }
}

/// "steps" into spec.steps: each parsed with the steps before it known; names unique.
void parse_steps(const Obj& top, CaseSpec& spec) {
  const std::size_t n = top.at("steps").expect_array(1, 10000);
  for (std::size_t i = 0; i < n; ++i)
    spec.steps.push_back(case_parse::parse_step(
        top.element("steps", i, {"name", "type", "long_term", "time_period_s", "increment", "boundary", "contact",
                                 "output", "steady_state", "damping", "newmark"}),
        spec));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < i; ++k)
      if (spec.steps[i].name == spec.steps[k].name)
        top.fail("steps[" + std::to_string(i) + "].name", "duplicate step name \"" + spec.steps[i].name + "\"");
}

}  // namespace

CaseSpec parse_case_json(const std::string& text, const std::filesystem::path& file) {
  const case_parse::Context ctx{file.string(), file.parent_path()};
  const json root = parse_json_finite(text, ctx.source);
  const Obj top(root, ctx, "", {"description", "mesh", "material", "sets", "amplitudes", "steps", "solver"});
  CaseSpec spec;
  spec.file = file;
  if (top.has("description")) spec.description = top.string("description");
  spec.mesh = case_parse::parse_mesh(top.child("mesh", {"generate", "inp", "stl", "formulation", "type", "elset",
                                                        "max_volume_mm3", "max_radius_edge", "min_dihedral_deg"}));
  spec.material_file = top.child("material", {"file"}).file("file");
  if (top.has("sets")) spec.sets = case_parse::parse_sets(top);
  if (top.has("amplitudes")) spec.amplitudes = case_parse::parse_amplitudes(top);
  parse_steps(top, spec);
  if (top.has("solver"))
    spec.solver = case_parse::parse_solver(top.child(
        "solver", {"threads", "linear_solver", "petsc_options", "residual_tolerance", "correction_tolerance", "max_iterations",
                   "max_cutbacks", "cutback_factor", "growth_factor", "newton", "max_contraction"}));
  return spec;
}

CaseSpec read_case_file(const std::filesystem::path& file) {
  return parse_case_json(io::read_text_file(file.string()), file);
}

}  // namespace cushion::solver
