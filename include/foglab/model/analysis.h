// foglab — the whole identification of a static recording (the lab
// manual's lab 2; conventions in docs/conventions.md): systematic part,
// statistics on the residual, noise-model fit, the lab's graphical
// readings, the random-bias question and the class.
//
//   1. temperature polynomial (systematic.h), when a temperature is given;
//   2. its residual: Welch PSD (two-sided, log-smoothed for display) and the
//      overlapping Allan deviation with 95 % intervals (stats/);
//   3. the joint noise-model fit (noise_fit.h), allowing for what removing
//      the polynomial did to each term, and with it the systematic fit's
//      standard errors; the automatic degree comes from a first, quick noise
//      model of the cubic fit's residual (deviations only);
//   4. graphical readings (readings.h), ADEV minimum = bias instability;
//   5. Table 1 class from that minimum and the ARW (N/60).
#pragma once

#include <exception>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "foglab/core/accuracy_class.h"
#include "foglab/model/noise_fit.h"
#include "foglab/model/output_quantisation.h"
#include "foglab/model/psd_allan.h"
#include "foglab/model/readings.h"
#include "foglab/model/spikes.h"
#include "foglab/model/steps.h"
#include "foglab/model/systematic.h"
#include "foglab/model/temperature_quantisation.h"
#include "foglab/stats/allan.h"
#include "foglab/stats/allan_drift.h"
#include "foglab/stats/psd.h"

namespace foglab::model {

struct AnalysisOptions {
  SystematicOptions systematic;
  stats::TauGrid grid;                ///< for the Allan deviation (default octave, >= 10 clusters)
  std::size_t psd_segment = 0;        ///< Welch segment (0: automatic, psd.h)
  double psd_bins_per_decade = 20.0;  ///< log smoothing for display and readings
  NoiseFitOptions noise_fit;
  /// The noise fit also uses the longer taus down to this many clusters
  /// (the reported Allan deviation keeps grid.min_clusters).
  std::int64_t fit_min_clusters = 3;
  /// A record with gaps: the share of an Allan cluster's samples that may be
  /// missing, the cluster's mean taken over those present (stats/allan.h,
  /// "Clusters that miss a few samples"); 0: Stable32's pooled stretches.
  double max_missing_share = 0.01;
  /// Gaps (by Gap::before_sample) that no Allan term may span all the same;
  /// analyze() adds those across which the bias jumps (steps.across_gaps:
  /// levelled nowhere, a spanning term would count the jump as noise).
  std::vector<std::int64_t> unbridged_gaps;
  /// Block means used for the detrending factors (systematic.h).
  int detrend_blocks = 512;
  SpikeOptions spikes;  ///< isolated outliers, found and replaced first (spikes.h)
  stats::AllanDriftOptions drift;  ///< the stationarity check of the short taus
  StepOptions steps;    ///< bias steps, found and levelled next (steps.h)
};

/// The evidence behind the random-bias answer.
struct RandomBiasEvidence {
  double deviance_none = 0.0;          ///< best model without random bias (NaN if none fitted)
  double deviance_wiener = 0.0;        ///< best model with a Wiener term (NaN if none admissible)
  double deviance_gauss_markov = 0.0;  ///< best with a Gauss-Markov term (NaN if none admissible)
  double criterion_none = 0.0, criterion_wiener = 0.0, criterion_gauss_markov = 0.0;
  /// Log-log slope of the ADEV over its last three points (+0.5 Wiener,
  /// turning negative after a Gauss-Markov hump).
  double adev_end_slope = 0.0;
  /// Log-log slope of the raw PSD over its lowest decade (-2 Wiener, about 0
  /// on a Gauss-Markov plateau below 1/(2 pi Tc)).
  double psd_low_frequency_slope = 0.0;
  Message summary;  ///< one sentence
};

struct AnalysisResult {
  double sample_rate_hz = 0.0;  ///< [Hz]
  std::int64_t samples = 0;     ///< samples present (without the gaps')
  double duration_s = 0.0;      ///< [s] the span, gaps included
  std::optional<SystematicFit> systematic;  ///< empty without temperature
  stats::PsdResult psd;                     ///< Welch PSD of the residual, (deg/h)^2/Hz two-sided
  stats::PsdResult psd_smoothed;            ///< the same, log-smoothed
  stats::AllanResult allan;                 ///< OADEV of the residual with intervals
  /// Whether the short taus' Allan variance trends over the record
  /// (stats/allan_drift.h), on the rate without its spikes and steps.
  stats::AllanDrift allan_drift;
  NoiseFitResult noise;
  AdevReadings adev_readings;
  PsdReadings psd_readings;
  double arw_deg_sqrt_h = 0.0;            ///< N/60 of the fit
  /// [deg/h] ADEV minimum over the taus beyond the output filter's memory
  /// (all of them without a filter: model/readings.h)
  double bias_instability_deg_h = 0.0;
  double bias_instability_tau_s = 0.0;    ///< [s]
  bool bias_instability_at_edge = false;  ///< minimum at the end of the taus read
  /// [s] The shortest tau the minimum is read from (0: every tau;
  /// NoiseFitResult::filter_memory_end_tau_s; AdevReadings::from_tau_s).
  double bias_instability_from_tau_s = 0.0;
  RandomBiasEvidence evidence;
  Spikes spikes;                           ///< what was found (and replaced) before the analysis
  BiasSteps steps;                         ///< the same for bias steps (levelled)
  OutputQuantisation output_quantisation;  ///< the output word's LSB, when the samples show one
  /// The temperature channel's step, when its readings show one (the
  /// temperature law is then fitted against the temperature between them).
  TemperatureQuantisation temperature_quantisation;
  std::vector<Gap> gaps;                   ///< the record's gaps, as given (core/gaps.h)
  ClassVerdict verdict;
  /// The manual's eq. (17): the Allan deviation the fitted PSD implies,
  /// against the measured one (psd_allan.h).
  PsdAllanCheck psd_allan;
  std::vector<Message> notes;  ///< what the program decided and why
};

/// Analyses a rate record [deg/h] sampled at `sample_rate_hz`, with the
/// temperature [degC] at the same instants (empty span: no temperature).
/// `rate_deg_h` is consumed (it holds the residual or its angle record
/// afterwards); it needs no copy, and with room for one more sample none is
/// made. The automatic degree runs a second array of the record's size and
/// uses two threads.
/// `gaps` (core/gaps.h) are the stretches of missing samples between the
/// samples given: the statistics pool the contiguous stretches (allan.h,
/// psd.h), spike and step times count the missing samples, and a note says
/// so. The temperature, when given, pairs with the samples present.
/// Throws UsageError / DataError as the steps do (e.g. too short a record).
AnalysisResult analyze(std::vector<double>& rate_deg_h, std::span<const double> temperature_c,
                       double sample_rate_hz, const AnalysisOptions& options = {},
                       std::span<const Gap> gaps = {});

/// One record of several analysed together (analyze_records()).
struct RecordToAnalyse {
  std::vector<double> rate_deg_h;     ///< consumed, as by analyze() (an accelerometer's in m/s^2)
  std::vector<double> temperature_c;  ///< empty: none
  double sample_rate_hz = 0.0;
  std::vector<Gap> gaps;
};

/// What a work queue (run_work_queue()) does once a job has failed.
enum class OnFailure {
  stop,        ///< start no new job; the running ones finish
  keep_going,  ///< run every job
};

/// Runs `job(k)` for k = 0 .. count-1 on `workers` threads taking the next
/// job as they finish one (`workers` 0: one per core; never more than
/// `count`). The cores are shared out between the workers for the
/// parallel parts of each job (each worker's OpenMP teams get cores /
/// workers threads, at least one), so that the machine is neither idle
/// nor oversubscribed. Returns each job's exception, null for a job that
/// succeeded or (OnFailure::stop) was never started.
std::vector<std::exception_ptr> run_work_queue(std::size_t count,
                                               const std::function<void(std::size_t)>& job,
                                               unsigned workers = 0,
                                               OnFailure on_failure = OnFailure::stop);

/// Analyses `count` records, several at a time (run_work_queue()): a record is loaded by
/// `load(k)` (k = 0 .. count-1) in the worker that analyses it, so reading
/// too runs in parallel and at most `workers` records are in memory at
/// once. `done(k)` (optional) is called in the worker once record k is analysed,
/// for progress. The results come in record order. When a load or an
/// analysis throws, no new record is started, the running ones finish,
/// and the first error in record order is rethrown; a UsageError or
/// DataError with `label(k) + ": "` in front of its message when `label`
/// is given.
std::vector<AnalysisResult> analyze_records(
    std::size_t count, const std::function<RecordToAnalyse(std::size_t)>& load,
    const AnalysisOptions& options = {}, unsigned workers = 0,
    const std::function<void(std::size_t)>& done = {},
    const std::function<std::string(std::size_t)>& label = {});

}  // namespace foglab::model
