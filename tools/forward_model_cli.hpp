#pragma once
/// The forward-model options `cushion compare` and `cushion diagnose` share, so that both run every test
/// with the same schedule (calibration/compare.hpp). The dynamic test's cycles per frequency and fitted cycles
/// come from the campaign (keys cycles, fit_cycles); only the time step is a model setting.
#include <CLI/CLI.hpp>

#include "calibration/compare.hpp"

namespace cushion::tools {

inline void add_forward_model_options(CLI::App* sub, calibration::CompareOptions& o) {
  sub->add_option("--steps-per-cycle", o.dynamic_steps_per_cycle,
                  "model: time steps per sine cycle of a dynamic test (default " +
                      std::to_string(calibration::CompareOptions{}.dynamic_steps_per_cycle) +
                      "; cycles per frequency and fitted cycles: the campaign's)")
      ->check(CLI::Range(16, calibration::max_steps_per_cycle));
  sub->add_option("--transient-steps-per-cycle", o.dynamic_transient_steps_per_cycle,
                  "model: time steps per sine cycle of the cycles before the fitted ones (default " +
                      std::to_string(calibration::CompareOptions{}.dynamic_transient_steps_per_cycle) +
                      "; they only set the state the fitted cycles start from)")
      ->check(CLI::Range(8, calibration::max_steps_per_cycle));
  sub->add_option("--preload-rate", o.preload_rate_mm_min,
                  "model: preload ramp speed [mm/min] of dynamic tests whose campaign entry gives no preload_rate_mm_min "
                  "(default " + std::to_string(static_cast<int>(calibration::CompareOptions{}.preload_rate_mm_min)) + ")")
      ->check(CLI::PositiveNumber);
}

}  // namespace cushion::tools
