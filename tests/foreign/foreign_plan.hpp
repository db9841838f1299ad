#pragma once
/// Test-data generation for the diagnose benchmark (issue 15), INDEPENDENT of cushion's material/ and
/// calibration/: the test plan of a campaign, its noise-free records, and how far two sets of records lie apart in
/// noise units (the measure every effect is scaled by).
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "foreign_effects.hpp"
#include "foreign_foam.hpp"
#include "foreign_machine.hpp"

namespace foreign_bench {

struct TestPlan {
  Specimen specimen;
  NoiseModel noise;
  std::vector<QuasiStaticProtocol> quasi_static;
  std::vector<DynamicProtocol> dynamic;
  /// The manifest leaves out the dynamic protocol keys (cycles, fit_cycles, preload_rate_mm_min,
  /// dwell_before_sweep_s, amplitude_convention) and each campaign runs its own (drawn_protocol); truth.json
  /// records what was run. false: the standard protocol, every key recorded.
  bool unrecorded_protocol = false;
  /// With unrecorded_protocol: the written acceleration_amplitude_m_s2 is the PEAK amplitude (half the
  /// peak-to-peak one the machine ran), as a lab that says "amplitude" for the peak writes it. Per campaign.
  bool amplitude_written_as_peak = false;
  /// Tests written besides the plan's (the test diagnose proposes to separate two explanations), each with its own
  /// noise stream from 200 on: the truth is drawn and scaled on the plan's tests only, so a campaign with extra tests
  /// has the same truth and the same records of the plan's tests as without.
  std::vector<QuasiStaticProtocol> extra_quasi_static;
  std::vector<DynamicProtocol> extra_dynamic;
};

/// The noise-free records of every test of a plan (extra tests excluded), in plan order.
struct PlanRecords {
  std::vector<QuasiStaticRecord> quasi_static;
  std::vector<DynamicRecord> dynamic;
};

PlanRecords simulate_noise_free(const BaseFoam& foam, const std::vector<EffectSpec>& effects, const TestPlan& plan);

/// Per test, how far `with` lies from `base` in noise units (noise of `base`): quasi-static RMS(dF)/RMS(force sd)
/// over the samples both records have; dynamic max(RMS(d|E*|)/RMS(sd |E*|), RMS(d phase)/RMS(sd phase)).
std::map<std::string, double> ratios_between(const PlanRecords& base, const PlanRecords& with, const TestPlan& plan);

/// The noise-normalised differences model - data, one per measured value of `data` [-]: every quasi-static sample
/// of the data record (force sd of the data; a model record that lifted off earlier reads 0 N there, as a platen
/// that only pushes), |E*| and phase at every frequency (their sd from the data's force noise).
Eigen::VectorXd normalised_differences(const PlanRecords& model, const PlanRecords& data, const TestPlan& plan);

}  // namespace foreign_bench
