// foglab — what a change of condition did to a gyro: two analyses of the
// same gyro compared (the lab manual's lab 2, item 2.4: how the temperature
// ramp changed the systematic bias, the white noise, the bias instability
// and the random bias).
//
// Every verdict is data: an estimate "changed" when the 95 % intervals of
// the two runs do not overlap and is "unchanged within the uncertainty" when
// they do; a random-bias answer changed when the two runs chose different
// processes; a term changed when only one run resolves it. The reports
// (report/lab2.h) turn this into sentences.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "foglab/core/accuracy_class.h"
#include "foglab/core/noise_model.h"
#include "foglab/model/analysis.h"

namespace foglab::model {

/// Whether an estimate moved between the two runs.
enum class Change {
  unchanged,       ///< the 95 % intervals overlap
  changed,         ///< they do not
  not_comparable,  ///< a run has no (finite) interval
};
/// "unchanged", "changed", "not_comparable".
std::string_view to_string(Change change);

/// One estimate in both runs, with 95 % intervals (NaN where there is none).
struct ValueChange {
  double before = 0.0, before_low = 0.0, before_high = 0.0;
  double after = 0.0, after_low = 0.0, after_high = 0.0;
  double relative = 0.0;  ///< after / before - 1
  Change verdict = Change::not_comparable;
};

/// The values and the verdict of their intervals.
ValueChange compare_values(double before, double before_low, double before_high, double after,
                           double after_low, double after_high);

/// The systematic part of both runs (each fitted a temperature polynomial).
struct SystematicChange {
  double span_before_c = 0.0, span_after_c = 0.0;  ///< [degC] temperature spans
  int degree_after = 0;                            ///< of the second run's polynomial
  /// [deg/h] how far that polynomial moves the bias over its temperatures
  /// (0 when it is a constant), and that over the run's bias instability.
  double polynomial_range_deg_h = 0.0;
  double range_over_bias_instability = 0.0;
  /// [deg/h] the bias at each run's mean temperature [degC], and their distance.
  double bias_before_deg_h = 0.0, bias_after_deg_h = 0.0;
  double t_ref_before_c = 0.0, t_ref_after_c = 0.0;
  double bias_difference_deg_h = 0.0;  ///< |after - before|
  /// [deg/h] the second run's model Allan deviation at half its length: the
  /// rms difference of the means of two adjacent half records, the scale on
  /// which the random bias moves a record's mean (flicker and a random walk
  /// have no finite mean, so no standard error of an intercept captures it).
  double wander_deg_h = 0.0;
  /// Whether the first run's polyfit constant term means anything (its
  /// temperature moved enough to extrapolate to 0 degC).
  bool lab_constant_meaningful_before = false;
};

/// What may change, in the order the comparison reports it.
enum class ChangedItem { white_noise, bias_instability, random_walk, random_bias_process, term };

/// A noise term (R or Q) that one run resolves and the other does not.
struct TermInOneRun {
  NoiseTerm term = NoiseTerm::ramp;
  bool in_after = false;  ///< resolved in the second run (else in the first)
  double value = 0.0;     ///< its estimate there
};

struct RunComparison {
  std::optional<SystematicChange> systematic;  ///< when both runs have a temperature
  std::optional<ValueChange> white_noise;      ///< N, when both runs resolve it
  ValueChange bias_instability;                ///< ADEV minimum with its 95 % interval
  RandomBiasProcess process_before = RandomBiasProcess::none;
  RandomBiasProcess process_after = RandomBiasProcess::none;
  std::optional<ValueChange> random_walk;      ///< K, when both runs chose a Wiener process
  std::optional<ValueChange> gm_sigma, gm_tc;  ///< when both chose Gauss-Markov (no verdict)
  std::vector<TermInOneRun> terms_in_one_run;  ///< R, Q
  AccuracyClass class_before = AccuracyClass::consumer;
  AccuracyClass class_after = AccuracyClass::consumer;
  /// What changed beyond the uncertainty, in order; empty: the change of
  /// condition left the random error unchanged (the temperature acts on the
  /// systematic part the polynomial captures).
  std::vector<ChangedItem> changed;
};

/// The 95 % interval [deg/h] of the Allan deviation at the reported tau
/// nearest `tau_s` (NaN without intervals).
std::pair<double, double> adev_interval_at(const stats::AllanResult& allan, double tau_s);

/// `before` (e.g. constant temperature) against `after` (the ramp).
RunComparison compare_runs(const AnalysisResult& before, const AnalysisResult& after);

}  // namespace foglab::model
