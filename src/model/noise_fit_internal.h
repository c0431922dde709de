// foglab — the steps of the noise-model fit (internal to the model module).
//
// fit_noise_model() (noise_fit.cc) runs its named steps in order, one file each:
//   1. gather_points()                 noise_fit_points.cc
//      the Allan variances, their edf and the detrending factors;
//   1b. find_bandwidth()               noise_fit_bandwidth.cc
//      the sensor's output bandwidth, when the short taus show one;
//   2. fit_candidates()                noise_fit_candidates.cc
//      every admissible subset of terms, by maximum gamma likelihood
//      (iteratively reweighted least squares, Tc profiled), best first;
//   3. collect_random_bias_evidence()  noise_fit_evidence.cc
//      the best candidate of each random-bias hypothesis;
//   4. set_chosen_intervals()          noise_fit_intervals.cc
//      95 % intervals of the chosen terms (sandwich covariance, the
//      Gauss-Markov profile);
//   5. bound_left_out_terms()          noise_fit_bounds.cc
//      status and one-sided bound of each term left out;
//   6. widen_over_near_candidates()    noise_fit_intervals.cc
//      intervals robust to the model choice, and widen_over_bandwidths()
//      (noise_fit_bandwidth.cc), the intervals over the bandwidths.
// The method is described in include/foglab/model/noise_fit.h.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "foglab/core/noise_model.h"
#include "foglab/core/numeric.h"
#include "foglab/model/noise_fit.h"

namespace foglab::model::detail {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// How each reweighting loop iterates (NoiseFitOptions).
struct IterationControl {
  double tolerance = 1e-10;
  int max_iterations = 200;
};

/// The data of one fit: Allan variances y [(deg/h)^2] at tau [s] with
/// degrees of freedom v, and the detrending factors of their tau points
/// (none: 1).
struct Points {
  std::vector<double> tau, y, v;
  std::vector<std::size_t> index;  ///< into the caller's tau points
  const DetrendFactors* detrend = nullptr;
  /// Greenhall's OADEV edf of each point for the noise types alpha = -2
  /// (random walk), -1 (flicker), 0 (white) and +2 (white phase); empty when
  /// the averaging factors are unknown (the data's own edf is used then).
  std::vector<std::array<double, 4>> edf_by_alpha;
  /// The averaging factors of the points and the angle samples of each of
  /// the record's contiguous stretches (one entry without gaps; both empty
  /// when unknown: no correlation across tau can be modelled).
  std::vector<std::int64_t> factors;
  std::vector<std::int64_t> segment_points;
  /// Each point's terms over those of a gap-free record of segment_points
  /// (stats::AllanResult::term_share: clusters that miss a few samples);
  /// empty: every term (the edf and covariance of segment_points hold).
  std::vector<double> term_share;
  /// What each point's edf was divided by for its terms' own spread
  /// (stats::AllanResult::edf_reduction: a resonance); empty: nothing. The
  /// candidates' edf and the points' covariance take it too.
  std::vector<double> edf_reduction;
  /// How every fit on these points iterates.
  IterationControl control;
  /// The known Allan variance at each point (the spectral lines'), added
  /// to every model; empty: none.
  std::vector<double> fixed_avar;
  /// The spectral lines' part of it at each point, per unit of
  /// `line_scale` (their Allan variance with the PSD's variance); empty:
  /// no lines.
  std::vector<double> line_avar;
  /// The factor on the lines' variance that fixed_avar holds.
  double line_scale = 1.0;
  /// The sensor bandwidth's factor on the white term at each point
  /// (core/sensor_bandwidth.h); empty: 1.
  std::vector<double> white_shape;
  /// Its factor on the flicker term (the filter acts on the output's flicker
  /// noise too); empty: 1.
  std::vector<double> flicker_shape;

  /// The sample interval tau0 [s] (0 when the averaging factors are unknown).
  double sample_interval_s() const {
    return factors.empty() ? 0.0 : tau.front() / static_cast<double>(factors.front());
  }

  /// The expected Allan variance of term t at point i per unit squared
  /// coefficient (Tc for the Gauss-Markov term), detrended.
  double basis_at(NoiseTerm t, std::size_t i, double tc) const {
    double b = unit_allan_variance(t, tau[i], tc);
    if (t == NoiseTerm::white && !white_shape.empty()) b *= white_shape[i];
    if (t == NoiseTerm::flicker && !flicker_shape.empty()) b *= flicker_shape[i];
    return detrend ? b * detrend->factor(t, index[i], tc) : b;
  }
};

/// A fitted subset of terms.
struct SubsetFit {
  NoiseTermSet terms;
  double tc = 0.0;                             ///< [s] Gauss-Markov Tc (1 without the term)
  std::array<double, kNoiseTerms.size()> c{};  ///< squared coefficients (GM: sigma^2)
  std::vector<double> mu;                      ///< the fitted Allan variances
  double deviance = kInf;
  bool feasible = false;
  std::vector<double> v;                    ///< the edf the fit used
  double neg2_loglik = kInf;                ///< -2 ln L of the gamma likelihood with those edf
  FitStatus status = FitStatus::converged;  ///< of its reweighting loop
  int iterations = 0;

  double squared(NoiseTerm t) const { return c[static_cast<std::size_t>(t)]; }
};

/// A term held at a given squared coefficient while the others are fitted
/// (profiling a bound).
struct FixedTerm {
  NoiseTerm term;
  double squared_coefficient;
};

/// What a fit does with a coefficient that comes out non-positive.
enum class NonPositive {
  infeasible,  ///< the subset is infeasible (its optimum is one of its subsets)
  drop_term,   ///< the term is left out and the rest refitted; it comes back while that
               ///< lowers the deviance (a non-negative fit; fit_subset())
};

// --- 1. points (noise_fit_points.cc) ----------------------------------------

/// The usable points (edf >= options.min_edf) of the caller's Allan
/// deviations; `factors` and `segment_points`, when known, give each point's
/// edf for the candidate models' noise types, scaled by `term_share` and
/// divided by `edf_reduction` (each one per caller's point, or empty).
/// Throws UsageError for mismatched sizes, non-positive values or fewer
/// than 3 usable points.
Points gather_points(std::span<const double> tau_s, std::span<const double> adev_deg_h,
                     std::span<const double> edf, std::span<const std::int64_t> factors,
                     std::span<const std::int64_t> segment_points,
                     std::span<const double> term_share, std::span<const double> edf_reduction,
                     const NoiseFitOptions& options, const DetrendFactors* detrend);

// --- 1b. the sensor bandwidth (noise_fit_bandwidth.cc) ----------------------

/// What the bandwidth search found: the estimate, and the (phi, T) the data
/// do not tell from it (reference deviance within the 95 % point of
/// chi-square with two degrees of freedom, times the dispersion; with one
/// for a filter known beyond its memory, whose c is its one parameter).
struct BandwidthSearch {
  BandwidthEstimate estimate;
  std::vector<SensorBandwidth> near;
  /// The reference model's deviance with the bandwidth found (without one
  /// when none is resolved); infinite when the search did not run.
  double reference_deviance = kInf;
};

/// The factor on the spectral lines' variance that the short taus ask for
/// (noise_fit_bandwidth.cc): the reference model's deviance profiled over
/// it (1/8 .. 8) with the bandwidth p holds; taken, and put into
/// p.fixed_avar, when it lowers that deviance by more than one parameter's
/// cost (the penalty, times the dispersion). Returns p.line_scale.
double find_line_scale(Points& p, const NoiseFitOptions& options);

/// Sets p.white_shape and p.flicker_shape for `bandwidth` (clears them
/// without one).
void set_bandwidth_shapes(Points& p, const SensorBandwidth& bandwidth);

/// A filter known beyond its memory is fitted only where the first kept tau
/// is at least this many c [samples] (noise_fit_bandwidth.cc says why).
constexpr double kMemoryReach = 3.0;

/// c [samples] of `bandwidth` (its filtered fraction included): the
/// correction c / m its white factor tends to far beyond its memory.
double memory_constant_of(const SensorBandwidth& bandwidth, double sample_interval_s);

/// The filter kinds find_bandwidth() tries.
enum class BandwidthKinds {
  established,       ///< the first-order low-pass and the moving average
  with_butterworth,  ///< those and the second-order Butterworth
  /// only a filter known beyond its memory (SensorBandwidth::
  /// memory_constant_samples), for points whose first taus are left out
  beyond_memory,
};

/// Looks for the sensor bandwidth in the short-tau points and, when the data
/// resolve it, sets p.white_shape and p.flicker_shape; returns what it found.
/// `gm_tc_s` > 0 adds a Gauss-Markov process of that correlation time to
/// the reference model.
BandwidthSearch find_bandwidth(Points& p, const NoiseFitOptions& options, double gm_tc_s = 0.0,
                               BandwidthKinds kinds = BandwidthKinds::with_butterworth);

/// Widens each resolved coefficient's interval (Tc held) to the union over
/// the bandwidths the data do not tell apart (the chosen terms refitted
/// with each): the white level is read through the filter's shape at the
/// first taus, and B, K and the rest share those taus with it.
void widen_over_bandwidths(const Points& p, const SubsetFit& chosen,
                           std::span<const SensorBandwidth> near, NoiseFitResult& r);

// --- 2. candidates (noise_fit_candidates.cc) --------------------------------

/// The gamma deviance of means mu on the points.
double deviance(const Points& p, const std::vector<double>& mu);

/// Maximum gamma likelihood of `terms` for a fixed Tc (and `fixed`, when
/// given, held at its value).
SubsetFit fit_subset(const Points& p, NoiseTermSet terms, double tc,
                     std::optional<FixedTerm> fixed = std::nullopt,
                     NonPositive non_positive = NonPositive::infeasible);

/// The same with Tc profiled when `terms` holds the Gauss-Markov term.
SubsetFit fit_subset_profiled(const Points& p, NoiseTermSet terms);

/// Whether the options allow the subset.
bool admissible(NoiseTermSet terms, const NoiseFitOptions& options);

/// Every admissible, feasible subset, fitted with the edf of its own model,
/// sorted by criterion, best first.
std::vector<SubsetFit> fit_candidates(const Points& p, const NoiseFitOptions& options);

/// -2 ln L + penalty * parameters.
double criterion(const SubsetFit& f, double penalty);

/// The fit's coefficients as a model.
NoiseModel to_model(const SubsetFit& f);

/// The fit as a candidate of the output.
CandidateModel candidate(const SubsetFit& f, double penalty);

// --- 3. evidence (noise_fit_evidence.cc) ------------------------------------

/// The best candidate of each random-bias hypothesis and the decision,
/// from `fits` sorted best first.
void collect_random_bias_evidence(std::span<const SubsetFit> fits, double penalty,
                                  NoiseFitResult& r);

// --- 4-6. intervals and bounds (noise_fit_intervals.cc, noise_fit_bounds.cc)

/// The chosen model with what its intervals need: its points (with its own
/// edf), the covariance of the points under it (none when the averaging
/// factors are unknown) and the fit's dispersion.
struct ChosenModel {
  Points points;
  const SubsetFit* fit = nullptr;
  std::optional<Eigen::MatrixXd> covariance;
  double dispersion = 1.0;
};

ChosenModel chosen_model(const Points& p, const SubsetFit& chosen, double dispersion);

/// The covariance [(deg/h)^4] of the points' Allan variance estimates under
/// the model `f` (its bandwidth shapes aside); needs p.factors.
Eigen::MatrixXd point_covariance(const Points& p, const SubsetFit& f);

/// The scaled gradients a_i = sqrt(v_i/2) d ln mu_i / d theta (rows), theta =
/// (ln c_j for the linear terms, then ln sigma^2, ln Tc): the Fisher
/// information of the gamma likelihood is A'A. Without `with_tc`, Tc is
/// held at its value. `order` receives the terms of the columns.
enum class TcColumn { with, without };
Eigen::MatrixXd log_parameter_gradients(const Points& p, const SubsetFit& f,
                                        std::vector<NoiseTerm>& order,
                                        TcColumn tc = TcColumn::with);

/// How the correlation R of the points' errors widens each parameter's
/// variance: the sandwich covariance's diagonal over the naive one.
Eigen::VectorXd sandwich_ratios(const Eigen::MatrixXd& a, const Eigen::MatrixXd& correlation);

/// The points' covariance divided by the standard deviations the fit's
/// weights assume (the R of sandwich_ratios()).
Eigen::MatrixXd standardised(const Eigen::MatrixXd& covariance, const Points& p,
                             const SubsetFit& f);

/// 4. The intervals of the chosen terms, as resolved estimates.
void set_chosen_intervals(const ChosenModel& chosen, const NoiseFitOptions& options,
                          NoiseFitResult& r);

/// 5. The status and one-sided 95 % bound of every term left out.
void bound_left_out_terms(const ChosenModel& chosen, const NoiseFitOptions& options,
                          NoiseFitResult& r);

/// 6. The union of the intervals of the candidates within
/// options.interval_window of the chosen one's criterion.
void widen_over_near_candidates(const Points& p, const ChosenModel& chosen,
                                std::span<const SubsetFit> fits, const NoiseFitOptions& options,
                                NoiseFitResult& r);

}  // namespace foglab::model::detail
