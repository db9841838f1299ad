// Requirement: bad input and failing runs shall end with one clear message naming the cause, and the
// frames written so far shall stay complete (the .pvd and every .vtu it lists readable by VTK).
// Checked: malformed JSON (line named), a missing set (key named), an element that inverts (the
// platen pushed past the bottom: material failure after the allowed cut-backs), a step that cannot
// converge (1 Newton iteration allowed on a nonlinear step), Ctrl-C (SIGINT raised in-process).
#include <csignal>

#include "io/input_error.hpp"
#include "solver/output/interrupt.hpp"
#include "solver/output/vtu_reader.hpp"
#include "test_run_support.hpp"

namespace cushion::solver {
namespace {

/// A 1 x 1 x 2 block compressed in two steps: "first" to `first_mm`, "second" to `second_mm`.
std::string two_step_case(double first_mm, double second_mm, const std::string& solver = "{}") {
  const std::string bc = R"([{"set": "bottom", "type": "fixed"}, {"set": "top", "dof": "z", "value_mm": )";
  return R"({"mesh": {"generate": {"type": "hex8", "box_mm": [0, 10, 0, 10, 0, 10], "elements": [1, 1, 2]}},
    "material": {"file": "foam.json"},
    "sets": {"bottom": "z == 0", "top": "z == 10"},
    "steps": [
      {"name": "first", "type": "static", "time_period_s": 1, "increment": {"initial_s": 0.25, "max_s": 0.25},
       "boundary": )" + bc + std::to_string(first_mm) + R"(}]},
      {"name": "second", "type": "static", "time_period_s": 1,
       "increment": {"initial_s": 0.25, "min_s": 0.01, "max_s": 0.25},
       "boundary": )" + bc + std::to_string(second_mm) + R"(}]}],
    "solver": )" + solver + "}";
}

/// Every frame of the .pvd readable, times increasing; returns the number of frames.
std::size_t check_frames_intact(const std::filesystem::path& out) {
  const auto entries = read_pvd(out / "results.pvd");
  double previous = -1.0;
  for (const PvdEntry& e : entries) {
    const VtuContents vtu = read_vtu(out / e.file);
    EXPECT_EQ(vtu.points.size(), 12u);  // 2 x 2 x 3 nodes
    EXPECT_TRUE(vtu.point_data.count("displacement_mm"));
    EXPECT_GT(e.time, previous);
    previous = e.time;
  }
  return entries.size();
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no exception";
}

TEST(RunErrors, MalformedCaseFileNamesTheLine) {
  const auto dir = test::scratch_dir();
  test::write_text(dir / "foam.json", test::foam_json(0.1, false));
  const auto file = test::write_text(dir / "case.json", "{\"mesh\": {\"generate\": \n {\"type\": \"hex8\",, }}");
  try {
    load_case(file);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("case.json"), std::string::npos) << m;
    EXPECT_NE(m.find(":2"), std::string::npos) << m;  // line 2
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
}

TEST(RunErrors, MissingSetNamesTheKey) {
  const auto dir = test::scratch_dir();
  test::write_text(dir / "foam.json", test::foam_json(0.1, false));
  std::string text = two_step_case(-1, -2);
  text.replace(text.find("\"top\", \"dof\""), 5, "\"tpo\"");
  const auto file = test::write_text(dir / "case.json", text);
  const std::string m = message_of([&] { load_case(file); });
  EXPECT_NE(m.find("steps[0].boundary[1].set"), std::string::npos) << m;
  EXPECT_NE(m.find("tpo"), std::string::npos) << m;
}

TEST(RunErrors, InvertingElementStopsAfterCutbacksWithCompleteFrames) {
  const auto dir = test::scratch_dir();
  test::write_text(dir / "foam.json", test::foam_json(0.1, false));
  // Second step pushes the top 12 mm down on a 10 mm block: elements must invert before the end.
  const auto file = test::write_text(dir / "case.json", two_step_case(-2, -12, R"({"max_cutbacks": 3})"));
  try {
    test::run_case(file, dir / "out");
    FAIL() << "no error";
  } catch (const AnalysisError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("step 'second'"), std::string::npos) << m;
    EXPECT_NE(m.find("cut-backs"), std::string::npos) << m;
    EXPECT_NE(m.find("failed"), std::string::npos) << m;  // material failure reported
    EXPECT_NE(m.find("frames written so far are complete"), std::string::npos) << m;
  }
  EXPECT_GE(check_frames_intact(dir / "out"), 6u);  // t = 0, 4 increments of "first", some of "second"
  // The history holds only converged rows: the top never passed the bottom.
  const CsvTable h = test::read_history(dir / "out");
  EXPECT_GT(h.rows(), 5u);
}

TEST(RunErrors, NonConvergingStepStopsWithCompleteFrames) {
  const auto dir = test::scratch_dir();
  test::write_text(dir / "foam.json", test::foam_json(0.1, false));
  // One Newton iteration and a tight tolerance: the nonlinear second step cannot converge.
  const auto file = test::write_text(
      dir / "case.json",
      two_step_case(-0.5, -6, R"({"max_iterations": 1, "residual_tolerance": 1e-12, "correction_tolerance": 1e-12})"));
  const std::string m = message_of([&] { test::run_case(file, dir / "out"); });
  EXPECT_NE(m.find("step 'second' at t = 1 s: no convergence after"), std::string::npos) << m;
  EXPECT_NE(m.find("not converged in 1 iterations"), std::string::npos) << m;
  EXPECT_NE(m.find("last residual"), std::string::npos) << m;
  EXPECT_GE(check_frames_intact(dir / "out"), 1u);  // at least the frame at t = 0
}

TEST(RunErrors, InterruptFinishesTheFrameAndThrows) {
  const auto dir = test::scratch_dir();
  test::write_text(dir / "foam.json", test::foam_json(0.1, false));
  const auto file = test::write_text(dir / "case.json", two_step_case(-1, -2));
  const InterruptGuard guard;
  std::raise(SIGINT);  // as if Ctrl-C came during the first increment
  ASSERT_TRUE(interrupt_requested());
  const std::string m = message_of([&] { test::run_case(file, dir / "out"); });
  clear_interrupt();
  EXPECT_NE(m.find("interrupted"), std::string::npos) << m;
  const auto entries = read_pvd(dir / "out" / "results.pvd");
  ASSERT_EQ(entries.size(), 2u);  // t = 0 and the first converged increment
  EXPECT_DOUBLE_EQ(entries[1].time, 0.25);
  EXPECT_EQ(check_frames_intact(dir / "out"), 2u);
  EXPECT_EQ(test::read_history(dir / "out").rows(), 2u);
}

}  // namespace
}  // namespace cushion::solver
