// Case files: the shipped cube case parses to the expected structs; every kind of bad input is an
// InputError that names the file and the key path; amplitude and ramp values are exact.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "io/input_error.hpp"
#include "solver/case/case_file.hpp"

namespace fs = std::filesystem;
using cushion::InputError;
using namespace cushion::solver;

namespace {

/// A fresh folder with an (unread) material file "foam.json" and a mesh file "part.inp".
fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("cushion_h6_case_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "foam.json") << "{}";
  std::ofstream(dir / "part.inp") << "*NODE\n";
  return dir;
}

nlohmann::json valid_case() {
  return nlohmann::json::parse(R"({
    "mesh": {"generate": {"type": "hex8", "box_mm": [0, 10, 0, 10, 0, 20], "elements": [1, 1, 2]}},
    "material": {"file": "foam.json"},
    "sets": {"bottom": "z == 0", "top": "z == 20"},
    "amplitudes": {"ramp": {"time_s": [0, 1, 3], "value": [0, 1, 0.5]}},
    "steps": [
      {"name": "load", "type": "static", "time_period_s": 1,
       "boundary": [{"set": "bottom", "type": "fixed"}, {"set": "top", "dof": "z", "value_mm": -5}]},
      {"name": "creep", "type": "visco", "time_period_s": 3,
       "increment": {"initial_s": 0.1, "min_s": 0.001, "max_s": 0.5, "max_increments": 50},
       "boundary": [{"set": "bottom", "type": "fixed"},
                    {"set": "top", "dof": "xyz", "value_mm": -5, "amplitude": "ramp"}],
       "output": {"frames_every_s": 0.5, "history": [{"set": "top", "quantities": ["U3", "RF3"]}]}}
    ]})");
}

/// Parses `j` written as "case.json" in a scratch folder; returns the InputError message ("" if none).
std::string error_of(const std::string& text, const std::string& name) {
  const fs::path dir = scratch(name);
  try {
    parse_case_json(text, dir / "case.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
std::string error_of(const nlohmann::json& j, const std::string& name) { return error_of(j.dump(2), name); }

/// Expects an InputError whose message starts with the case file and contains `key` and `words`.
void expect_error(const std::string& message, const std::string& key, const std::string& words) {
  ASSERT_FALSE(message.empty()) << "no InputError for " << key;
  EXPECT_NE(message.find("case.json:"), std::string::npos) << message;
  EXPECT_NE(message.find(key), std::string::npos) << "key '" << key << "' not named in: " << message;
  EXPECT_NE(message.find(words), std::string::npos) << "'" << words << "' not in: " << message;
}

}  // namespace

TEST(CaseFile, ValidCaseGivesPlainStructs) {
  const fs::path dir = scratch("valid");
  const CaseSpec spec = parse_case_json(valid_case().dump(), dir / "case.json");
  EXPECT_EQ(spec.mesh.source, MeshSpec::Source::generate);
  EXPECT_EQ(spec.mesh.generate.elements, (std::array<int, 3>{1, 1, 2}));
  EXPECT_EQ(spec.mesh.generate.high.z(), 20.0);
  EXPECT_EQ(spec.material_file, dir / "foam.json");
  ASSERT_EQ(spec.steps.size(), 2u);
  const StepSpec& load = spec.steps[0];
  EXPECT_EQ(load.type, StepSpec::Type::static_);
  // ABAQUS defaults: initial = max = period, min = 1e-5 period, 100 increments.
  EXPECT_EQ(load.increment.initial, 1.0);
  EXPECT_EQ(load.increment.max, 1.0);
  EXPECT_DOUBLE_EQ(load.increment.min, 1e-5);
  EXPECT_EQ(load.increment.max_increments, 100);
  EXPECT_EQ(load.boundary[0].kind, BoundarySpec::Kind::fixed);
  EXPECT_EQ(load.boundary[0].dofs, (std::array<bool, 3>{true, true, true}));
  EXPECT_EQ(load.boundary[1].dofs, (std::array<bool, 3>{false, false, true}));
  EXPECT_EQ(load.boundary[1].value, -5.0);
  EXPECT_EQ(load.boundary[1].key, "steps[0].boundary[1]");
  const StepSpec& creep = spec.steps[1];
  EXPECT_EQ(creep.type, StepSpec::Type::visco);
  EXPECT_EQ(creep.increment.initial, 0.1);
  EXPECT_EQ(*creep.output.frames_every, 0.5);
  EXPECT_EQ(*creep.boundary[1].amplitude, "ramp");
  EXPECT_EQ(history_columns(spec), (std::vector<std::string>{"top.U3_mm", "top.RF3_N"}));
  EXPECT_EQ(spec.solver.residual_tolerance, 0.005);
  EXPECT_EQ(spec.solver.linear_solver, SolverSpec::LinearSolver::automatic);
}

TEST(CaseFile, AmplitudeAndRampValuesAreExact) {
  const fs::path dir = scratch("amplitude");
  const CaseSpec spec = parse_case_json(valid_case().dump(), dir / "case.json");
  const Amplitude& a = spec.amplitudes.at("ramp");
  // Table (0,0) (1,1) (3,0.5): linear in between, constant outside (ABAQUS).
  EXPECT_DOUBLE_EQ(a.at(-1.0), 0.0);
  EXPECT_DOUBLE_EQ(a.at(0.25), 0.25);
  EXPECT_DOUBLE_EQ(a.at(1.0), 1.0);
  EXPECT_DOUBLE_EQ(a.at(2.0), 0.75);
  EXPECT_DOUBLE_EQ(a.at(10.0), 0.5);
  const BoundarySpec& ramped = spec.steps[0].boundary[1];  // no amplitude: linear from start value
  EXPECT_DOUBLE_EQ(prescribed_value(ramped, spec.amplitudes, 0.0, 0.25, 1.0, 0.0), -1.25);
  EXPECT_DOUBLE_EQ(prescribed_value(ramped, spec.amplitudes, -1.0, 0.5, 1.0, 7.0), -3.0);
  EXPECT_DOUBLE_EQ(prescribed_value(ramped, spec.amplitudes, 0.0, 1.0, 1.0, 0.0), -5.0);
  const BoundarySpec& scaled = spec.steps[1].boundary[1];  // value * a(step time)
  EXPECT_DOUBLE_EQ(prescribed_value(scaled, spec.amplitudes, 123.0, 2.0, 3.0, 1.0), -3.75);
  EXPECT_EQ(prescribed_value(spec.steps[1].boundary[0], spec.amplitudes, 4.0, 1.0, 3.0, 1.0), 0.0);
}

TEST(CaseFile, ShippedCubeCaseParses) {
  // The shipped text, placed where its relative material path resolves (independent of whether
  // the material file has been shipped yet).
  const fs::path shipped = fs::path(CUSHION_SOURCE_DIR) / "cases/cube_compression/case.json";
  std::ifstream in(shipped);
  ASSERT_TRUE(in) << shipped;
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const fs::path root = scratch("cube");
  fs::create_directories(root / "materials");
  fs::create_directories(root / "cube_compression");
  std::ofstream(root / "materials/paper_table3.json") << "{}";
  const CaseSpec spec = parse_case_json(text, root / "cube_compression/case.json");

  EXPECT_EQ(spec.mesh.generate.type, cushion::mesh::ElementType::hex8);
  EXPECT_EQ(spec.mesh.generate.high, cushion::mesh::Vec3(40, 40, 80));
  ASSERT_EQ(spec.steps.size(), 3u);
  const double speed = 120.0 / 60.0;  // 120 mm/min in mm/s
  EXPECT_DOUBLE_EQ(spec.steps[0].period, 60.0 / speed);
  EXPECT_DOUBLE_EQ(spec.steps[1].period, 2.0);
  EXPECT_DOUBLE_EQ(spec.steps[2].period, 60.0 / speed);
  for (const StepSpec& step : spec.steps) {
    EXPECT_EQ(step.type, StepSpec::Type::visco);
    const BoundarySpec& top = step.boundary.back();
    EXPECT_EQ(top.set, "top");
    EXPECT_EQ(top.dofs, (std::array<bool, 3>{false, false, true}));  // platen: x, y free
    EXPECT_EQ(step.boundary[2].set, "bottom");
    EXPECT_EQ(step.boundary[2].dofs, (std::array<bool, 3>{false, false, true}));  // roller
  }
  EXPECT_EQ(spec.steps[0].boundary.back().value, -60.0);  // 75 % of 80 mm
  EXPECT_EQ(spec.steps[1].boundary.back().value, -60.0);
  EXPECT_EQ(spec.steps[2].boundary.back().value, 0.0);
  EXPECT_EQ(spec.sets.at("top"), "z == 80");
  EXPECT_EQ(history_columns(spec), (std::vector<std::string>{"top.U3_mm", "top.RF3_N"}));
  // Loading rate of the ramp: 60 mm over 30 s.
  const auto& top = spec.steps[0].boundary.back();
  EXPECT_DOUBLE_EQ(prescribed_value(top, spec.amplitudes, 0.0, 1.0, spec.steps[0].period, 0.0), -speed);

  const fs::path material = fs::path(CUSHION_SOURCE_DIR) / "cases/materials/paper_table3.json";
  if (fs::exists(material)) {
    EXPECT_NO_THROW(read_case_file(shipped));
  }
}

TEST(CaseFile, BuildsGeneratedMeshWithSelectorSets) {
  const fs::path dir = scratch("build");
  const CaseSpec spec = parse_case_json(valid_case().dump(), dir / "case.json");
  const cushion::mesh::Mesh mesh = build_case_mesh(spec);
  EXPECT_EQ(mesh.num_elements(), 2u);
  EXPECT_EQ(mesh.num_nodes(), 12u);
  ASSERT_EQ(mesh.node_sets.at("top").size(), 4u);
  for (int n : mesh.node_sets.at("top")) EXPECT_EQ(mesh.nodes[n].z(), 20.0);
  EXPECT_THROW(check_set_names(spec, {"bottom"}), InputError);
}

TEST(CaseFile, UnknownKeyIsNamedWithSuggestion) {
  auto j = valid_case();
  j["steps"][1]["increment"]["initial_ss"] = 0.1;
  expect_error(error_of(j, "unknown"), "steps[1].increment.initial_ss", "did you mean 'initial_s'");
  j = valid_case();
  j["solvr"] = nlohmann::json::object();
  expect_error(error_of(j, "unknown_top"), "solvr", "unknown key");
}

TEST(CaseFile, MissingKeyIsNamed) {
  auto j = valid_case();
  j["steps"][0].erase("time_period_s");
  expect_error(error_of(j, "missing"), "steps[0].time_period_s", "missing key");
  j = valid_case();
  j.erase("material");
  expect_error(error_of(j, "missing_material"), "material", "missing key");
}

TEST(CaseFile, WrongTypeIsNamed) {
  auto j = valid_case();
  j["steps"][0]["time_period_s"] = "30";
  expect_error(error_of(j, "type"), "steps[0].time_period_s", "must be a number");
  j = valid_case();
  j["mesh"]["generate"]["elements"][1] = 2.5;
  expect_error(error_of(j, "integer"), "mesh.generate.elements[1]", "integer");
}

// Fuzzing/hand findings (issue 16): integer keys past their range wrapped silently when cast to int.
TEST(CaseFile, IntegerKeysPastTheirRangeAreRejected) {
  auto j = valid_case();
  j["solver"]["threads"] = 4294967295.0;
  expect_error(error_of(j, "threads"), "solver.threads", "must be an integer in [0, 1024]");
  j = valid_case();
  j["solver"]["max_iterations"] = 2147483648.0;
  expect_error(error_of(j, "iterations"), "solver.max_iterations", "must be an integer in [1, 1000]");
  j = valid_case();
  j["steps"][1]["increment"]["max_increments"] = 4294967296.0;
  expect_error(error_of(j, "increments"), "steps[1].increment.max_increments", "must be an integer in [1, 10000000]");
}

// Issue 16 (review for the fuzz harness): "elements" allowed 1e6 per axis, i.e. a 1e18-cell block that exhausts memory.
TEST(CaseFile, GeneratedMeshSizeIsBounded) {
  auto j = valid_case();
  j["mesh"]["generate"]["elements"] = {1000000, 1000000, 1000000};
  expect_error(error_of(j, "cells"), "mesh.generate.elements", "nx * ny * nz must be <= 1e7 cells, found 1e+18");
  j["mesh"]["generate"]["elements"] = {1000, 100, 100};  // exactly 1e7: accepted
  EXPECT_EQ(error_of(j, "cells_ok"), "");
}

TEST(CaseFile, WrongUnitIsNamed) {
  auto j = valid_case();
  j["steps"][0].erase("time_period_s");
  j["steps"][0]["time_period_ms"] = 1000;
  expect_error(error_of(j, "unit"), "steps[0].time_period_ms", "wrong unit 'ms'");
  j = valid_case();
  j["steps"][0]["boundary"][1].erase("value_mm");
  j["steps"][0]["boundary"][1]["value_m"] = -0.005;
  expect_error(error_of(j, "unit_m"), "steps[0].boundary[1].value_m", "'value_mm'");
}

TEST(CaseFile, NegativeOrInconsistentTimesAreRejected) {
  auto j = valid_case();
  j["steps"][1]["time_period_s"] = -3;
  expect_error(error_of(j, "negative"), "steps[1].time_period_s", "must be > 0");
  j = valid_case();
  j["amplitudes"]["ramp"]["time_s"] = {0, 2, 1};
  expect_error(error_of(j, "increasing"), "amplitudes.ramp.time_s", "strictly increasing");
  j = valid_case();
  j["steps"][1]["increment"]["min_s"] = 0.2;
  expect_error(error_of(j, "min"), "steps[1].increment.min_s", "must not exceed initial_s");
}

TEST(CaseFile, UnknownSetOrAmplitudeIsNamed) {
  auto j = valid_case();
  j["steps"][1]["boundary"][1]["set"] = "topp";
  expect_error(error_of(j, "set"), "steps[1].boundary[1].set", "unknown set \"topp\"");
  j = valid_case();
  j["steps"][1]["boundary"][1]["amplitude"] = "sine";
  expect_error(error_of(j, "amplitude"), "steps[1].boundary[1].amplitude", "unknown amplitude");
  j = valid_case();
  j["steps"][1]["output"]["history"][0]["set"] = "side";
  expect_error(error_of(j, "history"), "steps[1].output.history[0].set", "unknown set");
}

TEST(CaseFile, NonFiniteNumbersAreRejected) {
  auto text = valid_case().dump(2);
  const std::string from = "\"value_mm\": -5";
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), "\"value_mm\": NaN");
  expect_error(error_of(text, "nan"), "value_mm", "invalid JSON");
  auto j = valid_case().dump(2);
  j.replace(j.find(from), from.size(), "\"value_mm\": 1e999");
  expect_error(error_of(j, "overflow"), "value_mm", "invalid JSON");
}

TEST(CaseFile, StepTypeSpecificKeysAreChecked) {
  auto j = valid_case();  // a steady_state step takes its own keys, not those of a time step
  j["steps"][1]["type"] = "steady_state";
  expect_error(error_of(j, "steady"), "steps[1].time_period_s", "does not apply to a \"steady_state\" step");
  j = valid_case();  // contact is parsed for real now: its unknown keys are named
  j["steps"][0]["contact"] = nlohmann::json::array({{{"name", "platen"}, {"set", "top"}, {"colour", 1}}});
  expect_error(error_of(j, "contact"), "steps[0].contact[0]", "colour");
  j = valid_case();
  j["steps"][0]["type"] = "explicit";
  expect_error(error_of(j, "explicit"), "steps[0].type", "is not one of");
}

TEST(CaseFile, MeshAndFilesAreChecked) {
  auto j = valid_case();
  j["material"]["file"] = "nothere.json";
  expect_error(error_of(j, "material"), "material.file", "file not found");
  j = valid_case();
  j["mesh"]["generate"]["box_mm"] = {0, 10, 5, 5, 0, 1};
  expect_error(error_of(j, "box"), "mesh.generate.box_mm", "y0 < y1");
  j = valid_case();
  j["mesh"]["generate"]["type"] = "tet4";
  j["mesh"]["formulation"] = "fbar";
  expect_error(error_of(j, "fbar"), "mesh.formulation", "hex8");
  j = valid_case();
  j["mesh"] = {{"inp", "part.inp"}, {"generate", j["mesh"]["generate"]}};
  expect_error(error_of(j, "two_sources"), "mesh", "exactly one");
  j = valid_case();
  j["sets"]["top"] = "z === 20";
  expect_error(error_of(j, "selector"), "sets.top", "z === 20");
  // An .inp mesh may define its own sets: names are checked once the mesh is read.
  j = valid_case();
  j["mesh"] = {{"inp", "part.inp"}};
  j["steps"][0]["boundary"][1]["set"] = "NSET_FROM_INP";
  EXPECT_EQ(error_of(j, "inp"), "");
}

TEST(CaseFile, SyntaxErrorNamesLine) {
  const std::string message = error_of(std::string("{\n  \"mesh\": {,\n}"), "syntax");
  expect_error(message, "case.json:2:", "invalid JSON");
}

namespace {

/// valid_case() plus a third step: a steady-state sweep with the bottom shaken and the top held.
nlohmann::json sweep_case() {
  auto j = valid_case();
  j["steps"].push_back(nlohmann::json::parse(R"({"name": "sweep", "type": "steady_state", "steady_state": {
      "frequencies": {"start_Hz": 1, "end_Hz": 5, "step_Hz": 1},
      "excitation": {"set": "bottom", "dof": "z", "displacement_amplitude_mm": 0.01},
      "held": [{"set": "top", "dof": "z"}], "measure": "top", "area_mm2": 100, "thickness_mm": 20}})"));
  return j;
}

}  // namespace

TEST(CaseFile, SteadyStateStepGivesPlainStructs) {
  auto j = sweep_case();
  j["steps"][2]["steady_state"]["damping"] = {
      {"rayleigh_alpha_1_s", 180}, {"rayleigh_beta_s", 1e-4}, {"structural", 0.05}};
  j["steps"][2]["steady_state"]["base_stress"] = "as_left";
  const fs::path dir = scratch("sweep");
  const CaseSpec spec = parse_case_json(j.dump(), dir / "case.json");
  const SteadyStateSpec& s = spec.steps[2].steady_state;
  EXPECT_EQ(spec.steps[2].type, StepSpec::Type::steady_state);
  EXPECT_EQ(s.frequencies, (std::vector<double>{1, 2, 3, 4, 5}));
  EXPECT_EQ(s.excitation.set, "bottom");
  EXPECT_EQ(s.component(), 2);
  EXPECT_FALSE(s.from_acceleration);
  EXPECT_EQ(s.displacement, 0.01);
  EXPECT_EQ(s.damping.rayleigh_alpha, 180.0);
  EXPECT_EQ(s.damping.rayleigh_beta, 1e-4);
  EXPECT_EQ(s.damping.structural, 0.05);
  EXPECT_EQ(s.base_stress, BaseStress::as_left);
  EXPECT_EQ(s.key, "steps[2].steady_state");
}

TEST(CaseFile, SteadyStateWrongUnitIsNamed) {
  auto j = sweep_case();
  j["steps"][2]["steady_state"]["frequencies"].erase("start_Hz");
  j["steps"][2]["steady_state"]["frequencies"]["start_kHz"] = 0.001;
  expect_error(error_of(j, "sweep_khz"), "steps[2].steady_state.frequencies.start_kHz", "wrong unit 'kHz'");
  j = sweep_case();
  j["steps"][2]["steady_state"]["excitation"].erase("displacement_amplitude_mm");
  j["steps"][2]["steady_state"]["excitation"]["displacement_amplitude_m"] = 1e-5;
  expect_error(error_of(j, "sweep_m"), "steps[2].steady_state.excitation.displacement_amplitude_m",
               "this quantity is given as 'displacement_amplitude_mm' (millimetres)");
  j = sweep_case();
  j["steps"][2]["steady_state"]["damping"] = {{"rayleigh_beta_ms", 0.1}};
  expect_error(error_of(j, "sweep_ms"), "steps[2].steady_state.damping.rayleigh_beta_ms", "wrong unit 'ms'");
}

TEST(CaseFile, SteadyStateUnknownKeyIsNamedWithSuggestion) {
  auto j = sweep_case();
  j["steps"][2]["steady_state"]["base_stres"] = "relaxed";
  expect_error(error_of(j, "sweep_unknown"), "steps[2].steady_state", "did you mean 'base_stress'");
  j = sweep_case();
  j["steps"][2]["steady_state"]["excitation"]["colour"] = 1;
  expect_error(error_of(j, "sweep_colour"), "steps[2].steady_state.excitation", "colour");
  j = sweep_case();  // "structural" is a steady-state damping only
  j["steps"][1]["type"] = "dynamic";
  j["steps"][1]["damping"] = {{"structural", 0.05}};
  expect_error(error_of(j, "dynamic_structural"), "steps[1].damping", "structural");
}

TEST(CaseFile, SteadyStateEnumStringsAreCheckedWhenParsed) {
  auto j = sweep_case();
  j["steps"][2]["steady_state"]["base_stress"] = "long_term";
  expect_error(error_of(j, "sweep_base"), "steps[2].steady_state.base_stress", "long_term");
  j = sweep_case();
  auto& x = j["steps"][2]["steady_state"]["excitation"];
  x.erase("displacement_amplitude_mm");
  x["acceleration_amplitude_m_s2"] = 0.25;
  x["amplitude_is"] = "rms";
  expect_error(error_of(j, "sweep_rms"), "steps[2].steady_state.excitation.amplitude_is", "rms");
}

TEST(CaseFile, SteadyStateContactMustBeOfTheBaseState) {
  auto j = sweep_case();
  j["steps"][2]["steady_state"]["measure"] = {{"contact", "platen"}};
  expect_error(error_of(j, "sweep_contact"), "steps[2].steady_state.measure.contact",
               "\"platen\" is not a contact of the base state (contacts of the previous step: none)");
}

TEST(CaseFile, DynamicStepDampingAndHhtAlpha) {
  auto j = valid_case();
  j["steps"][1]["type"] = "dynamic";
  j["steps"][1]["damping"] = {{"rayleigh_alpha_1_s", 2}, {"rayleigh_beta_s", 1e-3}};
  j["steps"][1]["newmark"] = {{"alpha", -0.1}};
  const fs::path dir = scratch("dynamic");
  const DynamicSpec d = parse_case_json(j.dump(), dir / "case.json").steps[1].dynamic;
  EXPECT_EQ(d.damping.rayleigh_alpha, 2.0);
  EXPECT_EQ(d.damping.rayleigh_beta, 1e-3);
  EXPECT_EQ(d.damping.structural, 0.0);
  EXPECT_EQ(d.hht_alpha, -0.1);
  EXPECT_DOUBLE_EQ(d.gamma, 0.6);
}

// Issue 14: "linear_solver": "petsc" with its options string; the string's form is checked when parsed
// (whether PETSc knows the options is checked before the run, tests/petsc).
TEST(CaseFile, PetscOptionsAreParsedAndTheirFormChecked) {
  auto j = valid_case();
  j["solver"] = {{"linear_solver", "petsc"}, {"petsc_options", "-ksp_type cg -pc_type gamg -ksp_rtol 1e-10 -ksp_monitor"}};
  const CaseSpec spec = parse_case_json(j.dump(), scratch("petsc") / "case.json");
  EXPECT_EQ(spec.solver.linear_solver, SolverSpec::LinearSolver::petsc);
  EXPECT_EQ(spec.solver.petsc_options, "-ksp_type cg -pc_type gamg -ksp_rtol 1e-10 -ksp_monitor");
  j["solver"]["petsc_options"] = "-ksp_rtol -1e-3";  // a negative number is a value, not a name
  EXPECT_EQ(error_of(j, "petsc_negative"), "");
  j["solver"]["petsc_options"] = "ksp_type cg";
  expect_error(error_of(j, "petsc_name"), "solver.petsc_options", "'ksp_type' is not an option name");
  j["solver"]["petsc_options"] = "-ksp_type cg gmres";
  expect_error(error_of(j, "petsc_two_values"), "solver.petsc_options", "'gmres' is not an option name");
  j["solver"] = {{"linear_solver", "umfpack"}, {"petsc_options", "-ksp_type cg"}};
  expect_error(error_of(j, "petsc_other_solver"), "solver.petsc_options", "only with \"linear_solver\": \"petsc\"");
}
