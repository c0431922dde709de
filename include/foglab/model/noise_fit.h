// foglab — identifying the random error model from the Allan variance.
//
// The model (IEEE Std 952-1997 Annex C; core/noise_model.h, which is its
// one home), tau [s], rate [deg/h]:
//
//   AVAR(tau) = R^2 tau^2/2 + K^2 tau/3 + (2 ln2/pi) B^2 + N^2/tau + 3 Q^2/tau^2
//             + sigma^2 (Tc/tau)^2 (2 tau/Tc - 3 + 4 e^(-tau/Tc) - e^(-2 tau/Tc))
//
// with N white rate noise [deg/h/sqrt(Hz)], B flicker (bias instability)
// [deg/h], K rate random walk (Wiener) [deg/h/sqrt(s)], R rate ramp [deg/h/s],
// Q angle quantisation [deg/h*s] and a first-order Gauss-Markov random bias
// of standard deviation sigma [deg/h] and correlation time Tc [s].
//
// Estimator. Each overlapping Allan variance estimate is, to the usual
// approximation (NIST SP 1065 section 5.2.3), the model value times a
// chi-square variable with the estimate's equivalent degrees of freedom
// (edf) divided by the edf: a gamma variable of mean AVAR(tau) and shape
// edf/2. The fit maximises that likelihood over the tau grid (the points
// treated as independent), which is a weighted least-squares fit whose
// weights are the Allan variance's own uncertainty, 2 AVAR^2/edf, taken at
// the model (iteratively reweighted) — the weighting of the GMWM literature
// (Guerrier et al., "Wavelet-variance-based estimation for composite
// stochastic processes", JASA 2013), with the gamma deviance
//   D = sum_i edf_i (y_i/mu_i - 1 - ln(y_i/mu_i))
// as the measure of fit. The coefficients enter squared and linearly, so for
// a fixed Tc the fit is a positive weighted linear least-squares problem,
// solved by iterative reweighting until the fitted means change by less
// than `NoiseFitOptions::tolerance` (or `max_iterations` is reached: the
// result's status says which); Tc is profiled on a log grid and refined.
//
// Sensor bandwidth. A gyro's electronics low-pass filter its output, which
// lowers the first taus' Allan variance below N^2/tau. Before the
// candidates are fitted, the white term's shape is profiled over a filtered
// fraction phi and a time constant T, a moving average's length k, or a
// second-order Butterworth's cut-off f_c (core/sensor_bandwidth.h; the
// Butterworth is taken only when it fits better by more than one
// parameter's penalty) with a large
// model without a Gauss-Markov term; when the data resolve it (the deviance
// drops by more than two parameters' penalty, both as the independent
// points count it and with their correlation across tau) it is held for every
// candidate (on the white term and, with the same phi, on the flicker term:
// the filter acts on the output's flicker noise too, which matters where
// it has cut the white noise by an order of magnitude), N stays the white level, the Gauss-Markov
// search starts at the shortest tau, and every coefficient's interval (N's, B's, K's, ...)
// spans the bandwidths the data cannot tell apart (`NoiseFitResult::bandwidth`).
//
// When even so the chosen model's dispersion stays above 4 (an output
// filter none of the kinds follows, such as a cascade of two), the first
// one to four taus are left out and everything refitted: the fewest that
// bring the dispersion to 4 or below, else those that lower it most, when
// that is by more than 30 % (keeping eight points; not with spectral
// lines): `NoiseFitResult::first_taus_left_out`; the rest are fitted
// with a filter known beyond its memory, whose constant c the intervals
// span as they span the bandwidths above. A
// Gauss-Markov candidate whose Tc is within eight samples is no random
// bias but part of the output's bandwidth, and is left out.
//
// Spectral lines (model/spectral_lines.h) enter every model as known Allan
// variance; the factor on their PSD variance that the first taus ask for is
// profiled with the same reference model (kept when it gains more than one
// parameter's penalty), and the bandwidth is searched again after it
// (`NoiseFitResult::line_variance_scale`). A Gauss-Markov candidate whose
// Tc goes to the shortest searched is left out: a correlation below the
// first tau is the white level's and the bandwidth's, not a random bias.
// A rate ramp R is checked against the record's own least-squares slope
// (NoiseFitOptions::record_slope_deg_h_s; `NoiseFitResult::ramp_set_aside`).
//
// The edf of each point is Greenhall's for the noise type that dominates the
// candidate model there (white N: alpha 0, flicker B: -1, random walk K and
// ramp R: -2, quantisation Q: +2, Gauss-Markov: -2 below Tc, 0 above), fit
// and edf alternating a few times, so a random walk's long-tau points carry
// the few degrees of freedom they really have.
//
// Which terms are present: every admissible subset of {N, B, K, R, Q, GM}
// is fitted, a subset counting only when all its coefficients come out
// positive (otherwise its optimum is one of its subsets), and the subset
// minimising -2 ln L + penalty * (number of parameters) is chosen (an
// information criterion; the penalty 6 was set by the simulation study in
// docs/validation.md). Wiener and Gauss-Markov random bias are alternatives
// (the lab's question), not combined, unless the options allow it. A
// chosen Gauss-Markov model stands only when the record shows its hump
// turning down: its Allan variance peaks near 1.89 Tc, so Tc's 95 %
// interval must close below the longest tau / 1.89; otherwise, unless it
// beats the best Wiener candidate by more than 2 x penalty, the process is
// indistinguishable from a random walk there and that Wiener candidate is
// taken (NoiseFitResult::gauss_markov_set_aside says why).
//
// Uncertainty: the 95 % interval of a chosen term comes from the observed
// Fisher information of the gamma likelihood in log-parameter space,
// corrected for what the independent-points likelihood ignores: the
// overlapping estimates at neighbouring tau share most of their data
// (correlation 0.5 for white noise, 0.7 for flicker, 0.9 for a random walk
// between octaves). The covariance of the Allan variance estimates across
// tau under the chosen model, exact for Gaussian noise (Greenhall's
// structure-function form, src/model/allan_covariance.h), gives the
// sandwich covariance J^-1 (G'W Sigma W G) J^-1 of the fit (White 1982;
// Guerrier et al. 2013), and each parameter's variance is scaled by its
// ratio to the naive J^-1 (about 2 for N and Tc, 2.3 for B, 3 for K and
// sigma^2) and by the fit's dispersion D/(points - parameters) when that
// exceeds one, then mapped back (so the interval is positive and
// asymmetric).
// Without the averaging factors (the span form of fit_noise_model()) the
// covariance cannot be computed and `correlation_inflation` stands in.
// The Gauss-Markov pair is the exception: its likelihood is far from
// quadratic when the hump is only partly in the record, so Tc's interval is
// the profile-likelihood one (deviance within 3.84 x Tc's scale of its
// minimum) and sigma's the projection of the joint region (with sigma^2's
// scale); an end the data do not close (a process indistinguishable from a
// random walk) is infinite. A term left out gets a one-sided 95 % upper
// bound from the profile deviance (the value at which adding it costs 2.71
// in D, times its own sandwich scale in the enlarged model), reported as
// the interval [0, bound], and the status `upper_bound` when the data pull
// it above zero but not significantly, or `absent` when they pull it to
// zero.
// Those intervals hold for the chosen model; when the selection is wrong
// they miss (a small flicker term left out biases a Gauss-Markov sigma or a
// random walk up by 15-30 %; a random walk taken for a Gauss-Markov process
// is bounded beside the term that took its variance, a Gauss-Markov process
// taken for a random walk not at all). So every candidate whose criterion
// is within `interval_window` of the chosen one (docs/validation.md) also
// gives its intervals, and the reported ones are the unions: over the
// candidates holding a chosen term, and as the upper bound of a random-bias
// term left out (K; for a Gauss-Markov process, sigma's [0, bound] and the
// union of Tc's intervals). The estimates, statuses and the decision are the
// chosen model's.
#pragma once

#include <array>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "foglab/core/language.h"
#include "foglab/core/noise_model.h"
#include "foglab/core/sensor_bandwidth.h"
#include "foglab/core/spectral_line.h"
#include "foglab/stats/allan.h"

namespace foglab::model {

enum class TermStatus { resolved, upper_bound, absent };
/// "resolved", "upper_bound", "absent".
std::string_view to_string(TermStatus status);

/// One reported parameter.
struct ParameterEstimate {
  /// The estimate (resolved) or the 95 % upper bound (upper_bound); NaN when absent.
  double value = 0.0;
  /// The 95 % interval; for a term left out, the one-sided [0, upper_95]
  /// (NaN when no bound could be set), except the Gauss-Markov Tc's: the
  /// union of its intervals under the candidates that hold the term (NaN
  /// when none is close). A Gauss-Markov end the data do not close is
  /// infinite (ci95_high) or 0 (ci95_low).
  double ci95_low = 0.0;
  double ci95_high = 0.0;
  /// One-sided 95 % upper bound for a term left out (NaN when resolved or
  /// when no bound could be set, e.g. Gauss-Markov Tc).
  double upper_95 = 0.0;
  TermStatus status = TermStatus::absent;
};

struct NoiseFitOptions {
  /// Cost of one parameter in the selection criterion D + penalty * p.
  double penalty = 6.0;
  /// Multiplies the covariance of the chosen parameters, for the correlation
  /// of neighbouring tau estimates, when that correlation cannot be
  /// modelled (the averaging factors unknown: the span form of
  /// fit_noise_model()).
  double correlation_inflation = 3.0;
  /// Candidates whose criterion is within this of the chosen model's widen
  /// the reported intervals to the union of theirs (set by the simulation
  /// study).
  double interval_window = 6.0;
  bool allow_gauss_markov = true;
  /// Allow a Wiener and a Gauss-Markov term in the same model.
  bool allow_wiener_with_gauss_markov = false;
  /// Points whose edf is below this are left out of the fit.
  double min_edf = 1.0;
  /// The reweighting loop of each candidate has converged when no fitted
  /// mean changes by more than this, relative, from one iteration to the
  /// next (or the deviance by less than 1e-12 of itself).
  double tolerance = 1e-10;
  /// It stops after this many iterations whether or not it has converged
  /// (the status then says `iteration_limit`).
  int max_iterations = 200;
  /// Look for the sensor's output bandwidth in the short taus and model it
  /// (core/sensor_bandwidth.h); needs the averaging factors.
  bool model_bandwidth = true;
  /// With a bandwidth of a modelled kind, widen the resolved coefficients'
  /// intervals over the fit that assumes no kind (NoiseFitResult::
  /// shape_free_taus_left_out). false where only the model is wanted (the
  /// quick first look analyze() takes to choose the temperature degree).
  bool span_filter_shape = true;
  /// [deg/h/sqrt(Hz)] White rate noise of a known source outside the
  /// sensor, added to every model as the fixed Allan variance N_q^2 / tau:
  /// the rounding of a quantised output word (output_quantisation.h). N is
  /// then the sensor's own white level. 0: none.
  double known_white_deg_h_sqrt_hz = 0.0;
  /// [deg/h/s] The record's least-squares slope against time, and its span
  /// [s] (both NaN: unknown). A rate ramp R is a deterministic trend: the
  /// record's slope then estimates it. When the chosen model's R has its
  /// 95 % interval above |slope| + 3 standard deviations of the slope under
  /// the model's other terms (slope_standard_deviation()), the rise at the
  /// last taus is not a ramp in that record (a random walk's excursion, for
  /// one), and the models with R are left out
  /// (NoiseFitResult::ramp_set_aside). analyze() sets these where nothing
  /// but the mean was removed from the record.
  double record_slope_deg_h_s = std::numeric_limits<double>::quiet_NaN();
  double record_span_s = std::numeric_limits<double>::quiet_NaN();
};

/// The standard deviation [deg/h/s] of the least-squares slope against time
/// of a record of span T [s] whose noise is `model` (its stochastic terms:
/// white 12 N^2 / T^3, flicker 9 B^2 / (pi T^2), random walk 1.2 K^2 / T,
/// Gauss-Markov 288 sigma^2 / T^2 * int_0^1 exp(-x T / Tc) r(x) dx with
/// r(x) = 1/12 - x/4 + x^3/6, the slope weight's autocorrelation; the
/// continuous-time forms, from the weights' autocorrelation over each
/// term's autocovariance or semivariogram). The ramp R and Q add nothing.
double slope_standard_deviation(const NoiseModel& model, double span_s);

/// The sensor bandwidth the fit found (core/sensor_bandwidth.h): a part of
/// the white noise low-pass filtered before sampling. It is a property of
/// the white term: N stays the white level, the filter only lowers the
/// first taus' Allan variance.
struct BandwidthEstimate {
  bool resolved = false;  ///< the short taus show it (else the fields below are 0)
  SensorBandwidth bandwidth;
  double sample_interval_s = 0.0;  ///< [s] tau0 of the record
  double cutoff_hz = 0.0;          ///< [Hz] first-order cut-off 1 / (2 pi T)
  double lag1_correlation = 0.0;   ///< of the white noise's samples
  /// How much of the Allan variance at the first tau the filter takes away
  /// (1 - its factor there).
  double first_tau_reduction = 0.0;
  /// The drop of the deviance of the largest model without a random bias
  /// when the bandwidth is added (two parameters).
  double deviance_drop = 0.0;
  /// The same drop measured with the points' correlation across tau (the
  /// generalised-least-squares distance under the exact covariance of the
  /// points; NaN where it is unknown). Both must pass two parameters' cost.
  double correlated_deviance_drop = std::numeric_limits<double>::quiet_NaN();
  /// The best time constant sat at the longest the search allows (10 tau0):
  /// the correlation is longer than a filter's and is left to the other
  /// terms; the bandwidth is then not resolved.
  bool at_search_bound = false;
};

/// How removing a fitted polynomial (the temperature dependence) from the
/// record changes each term's expected Allan variance: the fit compares the
/// measured Allan variance of the residual with the model times these
/// factors (1 everywhere when nothing but the mean was removed). Computed by
/// detrend_factors() (systematic.h).
struct DetrendFactors {
  std::vector<double> tau_s;                  ///< [s] the fit's tau points
  std::array<std::vector<double>, 5> linear;  ///< N, B, K, R, Q: factor at each tau
  std::vector<double> gm_tc_s;                ///< [s] Gauss-Markov Tc grid, increasing
  std::vector<std::vector<double>> gm;        ///< [Tc index][tau index]
  /// The factor of `term` at tau point `index` (Tc for the Gauss-Markov
  /// term, interpolated in ln Tc, clamped at the grid's ends).
  double factor(NoiseTerm term, std::size_t index, double tc_s) const;
};

/// How the fit ended (after Ceres Solver's Solver::Summary).
enum class FitStatus {
  converged,        ///< the chosen model's reweighting loop met the tolerance
  iteration_limit,  ///< it stopped at max_iterations without meeting it
  degenerate,       ///< no candidate model could be fitted: the result holds none
};
/// "converged", "iteration_limit", "degenerate".
std::string_view to_string(FitStatus status);

/// One fitted candidate model (for the evidence in the output).
struct CandidateModel {
  NoiseTermSet terms;  ///< e.g. N+B+K
  NoiseModel model;
  double deviance = 0.0;  ///< gamma deviance D
  int parameters = 0;
  double criterion = 0.0;  ///< -2 ln L + penalty * parameters
  FitStatus status = FitStatus::converged;
  int iterations = 0;  ///< of its final reweighting loop
};

struct NoiseFitResult {
  FitStatus status = FitStatus::converged;
  /// How the fit ended, with the iterations and the tolerance, and how many
  /// candidates stopped at the iteration limit (core/language.h: in any language)...
  Message outcome;
  /// ... and in English, followed by the sentences below that are not empty (the JSON's):
  /// fit_sentence().
  std::string message;
  int iterations = 0;  ///< of the chosen model's final reweighting loop

  NoiseModel model;  ///< the chosen model (terms left out are 0)
  BandwidthEstimate bandwidth;  ///< the sensor's output bandwidth, on the white and flicker terms
  /// Narrow-band disturbances whose Allan variance the fit took as known
  /// (model/spectral_lines.h), with their variance as the fit used it
  /// (line_variance_scale times the PSD's for the lines that take it,
  /// SpectralLine::takes_variance_scale); empty when none were given.
  std::vector<SpectralLine> lines;
  /// The factor the fit found on the lines' variance as the PSD gave it:
  /// their Allan signature at the short taus fixes its amplitude better than
  /// the PSD bins of a broad line do (1 when the short taus do not ask for
  /// another, or without lines).
  double line_variance_scale = 1.0;
  /// Why a better-fitting Gauss-Markov model was set aside for the Wiener
  /// one (its Tc's interval does not close inside the record); empty when
  /// none was.
  Message gauss_markov_set_aside;
  /// Why the models with a rate ramp R were left out (the record's own
  /// slope does not support the ramp the chosen one had;
  /// NoiseFitOptions::record_slope_deg_h_s); empty when they were not.
  Message ramp_set_aside;
  /// How many of the first taus were left out because no modelled output
  /// filter follows them (0: none), and why.
  int first_taus_left_out = 0;
  Message first_taus_left_out_why;
  /// [s] The taus below this were left out: the geometric mean of the last
  /// one left out and the first one used (0 when none was). The fit's taus
  /// are the octave grid's, which need not be the reported ones.
  double left_out_below_tau_s = 0.0;
  /// [s] Where the output filter's memory ends: three times the found
  /// filter's c samples (core/sensor_bandwidth.h), or
  /// left_out_below_tau_s when the first taus were left out, the longer;
  /// 0 without either. Below it the filter, not the gyro's noise, sets the
  /// Allan deviation, so the bias instability is read beyond it
  /// (model/readings.h).
  double filter_memory_end_tau_s = 0.0;
  /// The resolved coefficients' intervals also span the fit that assumes no
  /// filter kind: this many first taus (those inside the found filter's
  /// memory) left out and the rest fitted with a filter known beyond its
  /// memory. -1: no such fit was made (no filter found, or the first taus
  /// already left out).
  int shape_free_taus_left_out = -1;
  /// [deg/h/sqrt(Hz)] N of that fit (NaN: none was made, or N is not
  /// resolved in it): beside N, how much the kind's shape decides it.
  double shape_free_n = std::numeric_limits<double>::quiet_NaN();
  /// [deg/h/sqrt(Hz)] NoiseFitOptions::known_white_deg_h_sqrt_hz as used.
  double known_white_deg_h_sqrt_hz = 0.0;
  ParameterEstimate N, B, K, R, Q, gm_sigma, gm_tc;
  RandomBiasProcess random_bias_process = RandomBiasProcess::none;
  NoiseTermSet terms;  ///< the chosen terms, e.g. N+B+K
  double deviance = 0.0;
  int points = 0;  ///< tau points used
  int parameters = 0;
  double dispersion = 1.0;  ///< max(1, D / (points - parameters))
  /// The best candidate of each random-bias hypothesis (no random bias, a
  /// Wiener term, a Gauss-Markov term), the evidence for the answer.
  CandidateModel best_without_random_bias, best_wiener, best_gauss_markov;
  bool has_candidate_without_random_bias = false;
  bool has_wiener_candidate = false, has_gauss_markov_candidate = false;
  std::vector<CandidateModel> candidates;  ///< every admissible subset, best first

  /// The estimate of one of kNoiseParameters (core/noise_model.h).
  const ParameterEstimate& estimate(const NoiseParameter& parameter) const;
  ParameterEstimate& estimate(const NoiseParameter& parameter);
};

/// How the fit ended and why terms or taus were set aside, in `language`: the outcome, then
/// first_taus_left_out_why, ramp_set_aside and gauss_markov_set_aside when not empty, joined
/// by "; " (NoiseFitResult::message is the English one).
std::string fit_sentence(const NoiseFitResult& r, Language language = Language::en);

/// The fitted Allan variance [(deg/h)^2] of one term at tau [s]: the
/// model's, with the bandwidth's factor on the white and flicker terms.
double fitted_allan_variance(const NoiseFitResult& fit, NoiseTerm term, double tau_s);
/// The sum over the terms, the spectral lines and the known white noise.
double fitted_allan_variance(const NoiseFitResult& fit, double tau_s);
/// The spectral lines' part of it.
double lines_allan_variance(const NoiseFitResult& fit, double tau_s);

/// Fits the model to Allan deviations `adev_deg_h` at `tau_s` with their
/// equivalent degrees of freedom `edf` (stats::AllanResult's fields).
/// Throws UsageError for mismatched sizes, fewer than 3 usable points or
/// non-positive values; a fit that cannot be done is the status
/// `degenerate`.
/// `detrend`, when given, holds the factors for the same tau points.
NoiseFitResult fit_noise_model(std::span<const double> tau_s, std::span<const double> adev_deg_h,
                               std::span<const double> edf, const NoiseFitOptions& options = {},
                               const DetrendFactors* detrend = nullptr);

/// The same on an Allan result computed with confidence intervals; the
/// Allan variance of `lines` (spectral lines of the same record) is taken as
/// known and added to every candidate model.
NoiseFitResult fit_noise_model(const stats::AllanResult& allan, const NoiseFitOptions& options = {},
                               const DetrendFactors* detrend = nullptr,
                               std::span<const SpectralLine> lines = {});

}  // namespace foglab::model
