#include "calibration/diagnose_output.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "calibration/compare_output.hpp"
#include "material/effect_catalog.hpp"

#include "io/text_support.hpp"

namespace cushion::calibration {

namespace fs = std::filesystem;

namespace {

std::string fmt(double v, int digits = 3) {
  std::ostringstream o;
  o << std::setprecision(digits) << v;
  return o.str();
}

nlohmann::json effects_json(const std::vector<material::EffectSpec>& effects) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& e : effects) {
    nlohmann::json j{{"kind", e.kind}};
    for (const auto& [k, v] : e.parameters) j[k] = v;
    a.push_back(j);
  }
  return a;
}

/// x, or null where it is not finite (JSON has no inf or NaN).
nlohmann::json finite_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

/// The values as a JSON array, NaN/inf as null (JSON has no NaN).
nlohmann::json finite_or_null(const std::vector<double>& v) {
  nlohmann::json a = nlohmann::json::array();
  for (double x : v) a.push_back(finite_or_null(x));
  return a;
}

/// The held-out table: per left-out test the chi2 of the candidate's and the reference's prediction.
std::string held_out_markdown(const std::vector<HeldOutCheck>& checks) {
  std::ostringstream o;
  o << "\n## Out-of-sample check (leave one test out)\n\n"
    << "Each test is left out in turn; the candidate and the reference (base refit) are refitted on the others and "
       "predict it. chi2 = sum of squared noise-normalised residuals of that prediction.\n\n";
  for (const auto& h : checks) {
    o << "### " << h.candidate << ": " << (h.confirmed ? "confirmed" : "not confirmed")
      << (h.failure.empty() ? "" : " (" + h.failure + ")") << "\n\n| left-out test | chi2 candidate | chi2 reference |\n|---|---|---|\n";
    for (std::size_t i = 0; i < h.tests.size(); ++i)
      o << "| " << h.tests[i] << " | " << fmt(h.chi2_candidate[i], 4) << " | " << fmt(h.chi2_reference[i], 4) << " |\n";
    o << "| total | " << fmt(h.total_candidate, 4) << " | " << fmt(h.total_reference, 4) << " |\n\n";
  }
  return o.str();
}

/// The protocol search: per unrecorded key, the dynamic chi2 with each value tried.
std::string protocol_markdown(const ProtocolSearch& p) {
  std::ostringstream o;
  o << "\n## Protocol assumptions (keys the campaign does not record)\n\n"
    << "Each key searched over plausible values with the baseline material, the others at their chosen values; chi2 of "
       "the dynamic tests (sum of squared noise-normalised residuals), " << p.runs << " runs, " << fmt(p.seconds, 2)
    << " s. A value replaces the default only when it lowers chi2 by more than the evidence threshold.\n\n"
    << "| key | tests | default | chosen | chi2 with each value |\n|---|---|---|---|---|\n";
  for (const auto& k : p.keys) {
    o << "| " << k.key << " | " << io::join(k.tests, ", ") << " | " << k.assumed << " | " << k.chosen << " |";
    for (const auto& v : k.tried) o << " " << v.label << ": " << (std::isfinite(v.chi2) ? fmt(v.chi2, 4) : "n/a") << ";";
    o << " |\n";
  }
  return o.str();
}

nlohmann::json protocol_json(const ProtocolSearch& p) {
  nlohmann::json keys = nlohmann::json::array();
  for (const auto& k : p.keys) {
    nlohmann::json tried = nlohmann::json::array();
    for (const auto& v : k.tried) tried.push_back({{"value", v.label}, {"chi2", finite_or_null(v.chi2)}});
    keys.push_back({{"key", k.key}, {"tests", k.tests}, {"assumed", k.assumed}, {"chosen", k.chosen}, {"tried", tried}});
  }
  return {{"keys", keys}, {"chi2_assumed", p.chi2_assumed}, {"chi2_chosen", p.chi2_chosen}, {"changed", p.changed()},
          {"runs", p.runs}, {"seconds", p.seconds}};
}

std::string rival_markdown(const Rival& r, const std::string& winner) {
  std::ostringstream o;
  o << "\n## Equally explained: " << winner << " or " << r.name << "\n\n"
    << "Tests this campaign does not have, run with both fitted models; separation = RMS difference of their "
       "predictions in units of the campaign's noise for that kind of test; chi2 = n separation^2, what data made by "
       "one model would add to the other's chi2 over the test's n residuals (above the evidence threshold 10: one such "
       "test tells them apart).\n\n"
    << "| test | separation | n | chi2 |\n|---|---|---|---|\n";
  for (const auto& t : r.tests)
    o << "| " << t.name << " | "
      << (std::isfinite(t.separation)
              ? fmt(t.separation, 3) + " | " + std::to_string(t.residuals) + " | " + fmt(t.delta_chi2(), 3)
              : "failed: " + t.failure + " | | ")
      << " |\n";
  return o.str();
}

nlohmann::json rival_json(const Rival& r) {
  nlohmann::json tests = nlohmann::json::array();
  for (const auto& t : r.tests)
    tests.push_back(
        {{"test", t.name},
         {"separation", finite_or_null(t.separation)},
         {"residuals", t.residuals},
         {"delta_chi2", std::isfinite(t.separation) ? nlohmann::json(t.delta_chi2()) : nlohmann::json(nullptr)},
         {"failure", t.failure}});
  return {{"name", r.name},
          {"delta_bic", r.delta_bic},
          {"least_gap", finite_or_null(r.least_gap)},
          {"separating_tests", tests}};
}

}  // namespace

nlohmann::json diagnosis_json(const Diagnosis& d) {
  nlohmann::json j;
  j["verdict"] = d.verdict;
  j["at_noise_level"] = d.at_noise_level;
  j["residuals"] = d.residuals;
  j["baseline_chi2"] = d.baseline_chi2;
  j["evidence"] = d.evidence;
  j["warnings"] = d.warnings;
  j["seconds"] = d.seconds;
  j["baseline"] = compare_json(d.baseline, "baseline");
  if (d.protocol) j["protocol"] = protocol_json(*d.protocol);
  j["winner"] = d.winner ? nlohmann::json(d.candidates[*d.winner].name()) : nlohmann::json(nullptr);
  j["winner_at_noise_level"] = d.winner_at_noise_level;
  j["rival"] = d.rival ? rival_json(*d.rival) : nlohmann::json(nullptr);
  j["fragment"] = d.fragment;
  auto reference_json = [](const CandidateFit& r) {
    return nlohmann::json{{"name", r.name()},
                          {"parameters", r.parameters},
                          {"chi2", r.chi2},
                          {"converged", r.converged},
                          {"delta_bic", finite_or_null(r.delta_bic)}};
  };
  if (d.base_refit) j["base_refit"] = reference_json(*d.base_refit);
  // step 2b: the reference a challenger is judged against (Prony times and hyperfoam exponents free too)
  if (d.polished_base_refit) j["polished_base_refit"] = reference_json(*d.polished_base_refit);
  j["held_out"] = nlohmann::json::array();
  for (const auto& h : d.held_out)
    j["held_out"].push_back({{"candidate", h.candidate}, {"tests", h.tests}, {"chi2_candidate", finite_or_null(h.chi2_candidate)},
                             {"chi2_reference", finite_or_null(h.chi2_reference)}, {"confirmed", h.confirmed}, {"possible", h.possible},
                             {"failure", h.failure}, {"seconds", h.seconds}});
  j["candidates"] = nlohmann::json::array();
  for (std::size_t i = 0; i < d.candidates.size(); ++i) {
    const CandidateFit& c = d.candidates[i];
    nlohmann::json jc{{"rank", i + 1},
                      {"name", c.name()},
                      {"parameters", c.parameters},
                      {"converged", c.converged},
                      {"supported", c.supported},
                      {"message", c.message},
                      {"chi2", c.chi2},
                      {"delta_bic", finite_or_null(c.delta_bic)},
                      {"evaluations", c.evaluations},
                      {"seconds", c.seconds},
                      {"effects", effects_json(c.effects)}};
    jc["support_note"] = c.support_note;  // why a passing candidate is not supported or ranked lower, else ""
    jc["polished"] = c.polished;  // step 2b: refitted with the base's Prony times and hyperfoam exponents free too
    jc["challenger"] = c.challenger;  // a near miss polished (--polish-challengers): judged against polished_base_refit
    if (c.polished && std::isfinite(c.delta_bic_unpolished)) jc["delta_bic_unpolished"] = c.delta_bic_unpolished;
    if (!c.compare.tests.empty()) jc["compare"] = compare_json(c.compare, c.name());
    j["candidates"].push_back(jc);
  }
  return j;
}

namespace {

/// What each value of the fragment's effects means: one line per key, from the catalogue.
std::string parameter_meanings(const nlohmann::json& fragment) {
  std::ostringstream o;
  o << "\nWhat the values mean:\n\n";
  for (const auto& effect : fragment.at("effects")) {
    const material::EffectInfo* info = material::find_effect(effect.at("kind").get<std::string>());
    if (!info) continue;
    for (const auto& p : info->parameters)
      if (effect.contains(p.name)) o << "- `" << info->kind << "." << p.name << "`: " << p.description << "\n";
  }
  return o.str();
}

}  // namespace

std::string diagnosis_markdown(const Diagnosis& d) {
  std::ostringstream o;
  o << "# cushion diagnose\n\n## Verdict\n\n" << d.verdict << "\n";
  if (!d.warnings.empty()) {
    o << "\n## Warnings\n\n";
    for (const auto& w : d.warnings) o << "- " << w << "\n";
  }
  if (d.protocol && !d.protocol->keys.empty()) o << protocol_markdown(*d.protocol);
  o << "\n## Baseline vs every test\n\n" << compare_table(d.baseline);
  o << "\n## Evidence in the data (signatures)\n\n";
  for (const auto& e : d.evidence) o << "- " << e << "\n";
  if (!d.candidates.empty()) {
    o << "\n## Candidates (refit of the effect's parameters only; base calibration kept; ref: the base refitted without effect)\n\n"
      << "dBIC = BIC(baseline) - BIC(candidate), BIC = chi2 + k ln N on noise-normalised residuals, N = " << d.residuals
      << ", baseline chi2/N = " << fmt(d.baseline_chi2 / std::max<std::size_t>(1, d.residuals)) << ".\n\n";
    std::vector<std::string> names;
    for (const auto& t : d.baseline.tests) names.push_back(t.name);
    o << "| rank | candidate | k | dBIC | chi2/N |";
    for (const auto& n : names) o << " " << n << " |";
    o << " status |\n|---|---|---|---|---|";
    for (std::size_t i = 0; i < names.size(); ++i) o << "---|";
    o << "---|\n| - | baseline | 0 | 0 | " << fmt(d.baseline_chi2 / d.residuals) << " |";
    for (const auto& t : d.baseline.tests) o << " " << fmt(t.noise_ratio(), 3) << " |";
    o << " |\n";
    // one row of the table: a reference fit or a candidate
    auto fit_row = [&](const CandidateFit& f, const std::string& rank, const std::string& name,
                       const std::string& status) {
      o << "| " << rank << " | " << name << " | " << f.parameters << " | "
        << (std::isfinite(f.delta_bic) ? fmt(f.delta_bic, 4) : "-") << " | "
        << (f.compare.tests.empty() ? "-" : fmt(f.chi2 / d.residuals)) << " |";
      for (std::size_t t = 0; t < names.size(); ++t)
        o << " " << (t < f.compare.tests.size() ? fmt(f.compare.tests[t].noise_ratio(), 3) : "-") << " |";
      o << " " << status << " |\n";
    };
    if (d.base_refit)  // the reference every effect must beat
      fit_row(*d.base_refit, "ref", d.base_refit->name(), "an effect must beat this by the evidence threshold");
    if (d.polished_base_refit)
      fit_row(*d.polished_base_refit, "ref*", "base refit polished (Prony times and exponents free too)",
              d.polished_base_refit->converged ? "a challenger must beat this by the evidence threshold"
                                               : d.polished_base_refit->message);
    for (std::size_t i = 0; i < d.candidates.size(); ++i) {
      const CandidateFit& c = d.candidates[i];
      std::string status = c.supported    ? "supported" + (c.support_note.empty() ? "" : " (" + c.support_note + ")")
                           : !c.converged ? c.message
                           : c.support_note.empty() ? "not supported"
                                                    : "not supported (" + c.support_note + ")";
      if (c.polished)
        status += std::string(" (polished") + (c.challenger ? " as a challenger, judged against ref*" : "") +
                  ": Prony times and exponents free too, dBIC " + fmt(c.delta_bic_unpolished, 4) + " before)";
      fit_row(c, std::to_string(i + 1), c.name(), status);
    }
    o << "\n(per-test columns: RMS error / measurement noise; 1 = noise level)\n";
  }
  if (!d.held_out.empty()) o << held_out_markdown(d.held_out);
  if (d.rival && d.winner) o << rival_markdown(*d.rival, d.candidates[*d.winner].name());
  if (d.winner) {
    const CandidateFit& w = d.candidates[*d.winner];
    o << "\n## Error per test and region with " << w.name() << "\n\n" << compare_table(w.compare);
    o << "\n## Change to make: add to the material file\n\n```json\n"
      << d.fragment.dump(2) << "\n```\n"
      << parameter_meanings(d.fragment)
      << "\n(material_extended.json is the baseline with this change; run `cushion compare material_extended.json "
         "...`.)\n";
  }
  return o.str();
}

void write_diagnosis_outputs(const Diagnosis& d, const fs::path& dir, const std::string& gnuplot) {
  fs::create_directories(dir);
  io::write_file_atomically(dir / "report.json", diagnosis_json(d).dump(2) + "\n");
  io::write_file_atomically(dir / "diagnosis.md", diagnosis_markdown(d));
  write_compare_outputs(d.baseline, "baseline", dir / "baseline", gnuplot);
  fs::remove(dir / "fragment.json");
  fs::remove(dir / "material_extended.json");
  if (d.winner) {
    io::write_file_atomically(dir / "fragment.json", d.fragment.dump(2) + "\n");
    material::write_material_file(d.extended, dir / "material_extended.json");
    write_compare_outputs(d.candidates[*d.winner].compare, d.candidates[*d.winner].name(), dir / "extended", gnuplot);
  }
}

}  // namespace cushion::calibration
