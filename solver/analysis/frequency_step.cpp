#include "solver/analysis/frequency_step.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "io/text_support.hpp"
#include "solver/dynamics/modes.hpp"

namespace cushion::solver {

std::unique_ptr<dynamics::LinearisedSystem> linearise_base_state(const AnalysisContext& ctx, const StepSpec& step,
                                                                 const Assembler& assembler, BaseStress stress) {
  const ModelState& model = ctx.model();
  try {
    auto points = dynamics::base_point_states(assembler, model.material, model.u, stress);
    return std::make_unique<dynamics::LinearisedSystem>(ctx.mesh(), assembler.sections(), std::move(points), model.u);
  } catch (const std::runtime_error& e) {
    throw AnalysisError("step '" + step.name + "': cannot linearise the base state: " + e.what());
  }
}

std::vector<double> natural_frequencies_with_held(const dynamics::LinearisedSystem& system, const std::vector<bool>& held,
                                                  const StepSpec& step) {
  std::vector<int> free;
  for (int d = 0; d < static_cast<int>(system.num_dofs()); ++d)
    if (!held[d]) free.push_back(d);
  try {
    return dynamics::natural_frequencies(system.long_term_stiffness(), system.mass(), free, static_cast<int>(free.size()));
  } catch (const std::invalid_argument& e) {
    throw AnalysisError("step '" + step.name + "': " + e.what());
  }
}

void FrequencyStep::run(AnalysisContext& ctx) {
  const FrequencySpec& s = spec_.frequency;
  const Assembler& assembler = *ctx.system(ctx.model().constrained).assembler;
  const auto system = linearise_base_state(ctx, spec_, assembler, BaseStress::relaxed);
  std::vector<bool> held(system->num_dofs(), false);
  for (const BoundarySpec& bc : spec_.boundary)
    for (int n : ctx.mesh().node_sets.at(bc.set))
      for (int c = 0; c < 3; ++c)
        if (bc.dofs[c]) held[DofMap::dof(n, c)] = true;
  const std::vector<double> f = natural_frequencies_with_held(*system, held, spec_);
  const auto n_free = std::count(held.begin(), held.end(), false);
  if (!ctx.output().writes()) return;  // another process of a distributed run writes
  const std::filesystem::path file = ctx.output().pvd_file().parent_path() / (spec_.name + "_frequencies.csv");
  std::ofstream out(file);
  out << "# cushion run " << ctx.spec().file.string() << ": step " << spec_.name << ", natural frequencies about t = "
      << io::format_double(ctx.model().time) << " s (long-term tangent, consistent mass, " << n_free
      << " free DOFs)\nmode,frequency_Hz,eigenvalue_rad2_s2\n";
  ctx.log() << "step '" << spec_.name << "' (frequency): " << n_free << " free DOFs\n";
  int mode = 0;
  for (double fk : f) {
    if (fk < s.low || (s.high > 0.0 && fk > s.high)) continue;
    if (++mode > s.modes) break;
    const double w = 2.0 * M_PI * fk;
    out << mode << "," << io::format_double(fk) << "," << io::format_double(w * w) << "\n";
    ctx.log() << "  mode " << mode << ": " << fk << " Hz\n";
  }
  if (!out) throw std::runtime_error(file.string() + ": cannot write");
}

std::unique_ptr<Step> make_frequency_step(const StepSpec& spec) { return std::make_unique<FrequencyStep>(spec); }

}  // namespace cushion::solver
