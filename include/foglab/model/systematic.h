// foglab — the systematic part of a static recording: bias and its
// temperature dependence (lab manual section 2.2, step 3: polyfit(T, Y, 2)).
//
// Model: rate_k = sum_{j=0..d} c_j (T_k - t_ref)^j + e_k, t_ref the mean
// temperature, fitted by ordinary least squares (Eigen's QR on the centred
// and scaled design). The noise e_k is NOT white — a gyro's random bias
// (flicker, Wiener, Gauss-Markov) is strongly correlated, and under a
// temperature ramp it is confounded with the temperature terms — so the
// standard errors of c_j come from the covariance the fitted noise model
// implies (noise_fit.h), not from the residual scatter:
//
//   Cov(c) = (X'X)^-1 X' Sigma X (X'X)^-1,
//
// with Sigma built on block means of the record from the phase structure
// function of each noise term (white, flicker, Wiener, Gauss-Markov,
// quantisation; docs/theory/systematic.md). A random-walk or flicker
// process has no finite variance, so the intercept's standard error counts
// only the stationary terms; the slopes' errors are complete.
//
// Degree: by default the degree d in 0..3 minimising the information
// criterion W_d + p d, where W_d is the Wald statistic (with the covariance
// above, so correlated noise is accounted for) of the coefficients above d in
// the cubic fit — the Wald approximation of the likelihood-ratio statistic
// -2 ln(L_d / L_3) — and p = 6.63, the 99 % point of chi-square with one
// degree of freedom: a coefficient must be significant at the 1 % level to
// enter. (BIC's ln(n) would count every sample as independent, which a
// random-walk bias is not; AIC's 2 lets one spurious term in six.) When the temperature barely
// moves (the spread of its block means below `min_span_c`) the fit falls back to a constant,
// whatever was asked, and says so. The lab's number — the constant term of polyfit(T, Y, 2) in raw
// degC — is reported from the quadratic fit in every case (with `lab_constant_meaningful` false on
// a thermostat run).
#pragma once

#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "foglab/model/noise_fit.h"

namespace foglab::model {

struct SystematicOptions {
  int degree = -1;          ///< -1: choose by the criterion; 0..3 forces it
  int max_degree = 3;       ///< highest degree the criterion considers (0..3)
  /// Lowest degree the criterion considers when the temperature moves
  /// (span >= min_span_c): a run through a temperature range is made to
  /// measure the linear coefficient, which is then reported with its
  /// standard error even when it is not significant (0: let the criterion
  /// drop it).
  int min_degree = 1;
  double min_span_c = 0.5;  ///< [degC] below this spread, fit a constant
  int blocks = 1024;        ///< block means used for the covariance
  /// Cost of one coefficient in the degree criterion (chi-square_1 at 99 %).
  double degree_penalty = 6.635;
};

struct SystematicFit {
  int degree = 0;                    ///< degree used
  std::vector<double> coefficients;  ///< c_j [deg/h/degC^j] about t_ref_c
  std::vector<double>
      standard_errors;      ///< [deg/h/degC^j] from the noise model (NaN before it is known)
  double t_ref_c = 0.0;     ///< [degC] mean temperature
  double bias_deg_h = 0.0;  ///< [deg/h] c_0: the bias at t_ref_c
  double temperature_span_c = 0.0;  ///< [degC] max - min of the block-mean temperature
  double temperature_min_c = 0.0, temperature_max_c = 0.0;  ///< [degC] of the block means
  /// Constant term of polyfit(T, Y, 2) in raw degC [deg/h] (the lab's number).
  double lab_constant_term_deg_h = 0.0;
  /// polyfit(T, Y, 2) in MATLAB order [p1 p2 p3].
  std::vector<double> lab_polyfit;
  bool lab_constant_meaningful = true;  ///< false when the span is below min_span_c
  bool constant_fallback = false;       ///< the span was too small for a slope
  bool degree_chosen = false;           ///< by the criterion (not forced)
  /// W_d + 6.63 d, d = 0..max: for a chosen degree, and beside a forced one
  /// as its verdict (empty when the temperature barely moves).
  std::vector<double> criterion;
  /// The degree the criterion chooses: the degree used when chosen (from
  /// min_degree up); beside a forced degree, what the data alone would keep
  /// (from 0 up: whether any temperature term stands out of the noise).
  /// -1 when the criterion was not evaluated.
  int criterion_degree = -1;
  /// The criterion's cost per coefficient (SystematicOptions::degree_penalty)
  /// when it was evaluated: a coefficient stands out of the noise when it is
  /// more than sqrt(penalty) standard errors from zero. NaN otherwise.
  double criterion_penalty = std::numeric_limits<double>::quiet_NaN();
  double residual_rms_deg_h = 0.0;      ///< [deg/h]
  Message note;                         ///< what was done, for the report
};

/// What every step of the temperature fit needs from one record, gathered
/// once (a few passes over the record, in parallel with thread-count
/// independent results): the mean temperature t_ref, the spread of the
/// block-mean temperature, and with u = (T - t_ref)/scale (scale the RMS of
/// T - t_ref) the sums of u^p (p = 0..6), of (y - mean y) u^j (j = 0..3) and
/// of (y - mean y)^2, and the block means of u^j (j = 0..3) for the
/// covariance (`blocks` blocks) and the detrending factors (`detrend_blocks`
/// blocks, at most a quarter of the samples). A fit of any degree, its
/// covariance and its detrending factors then cost no further pass over the
/// record. Keeps no reference to the arrays. Throws as fit_temperature().
class TemperatureRecord {
 public:
  TemperatureRecord(std::span<const double> rate_deg_h, std::span<const double> temperature_c,
                    double sample_rate_hz, int blocks = 1024, int detrend_blocks = 1024);

  double t_ref_c() const;  ///< [degC] mean temperature

  struct Sums;  ///< the sums (defined in systematic.cc)
  const Sums& sums() const { return *sums_; }

 private:
  std::shared_ptr<const Sums> sums_;
};

/// Least-squares fits of degree 0..max_degree; returns the fit of the
/// requested (or, for auto, the highest admissible) degree, without
/// standard errors. Throws UsageError for mismatched lengths, fewer than 8
/// samples or a degree outside 0..3; DataError for a non-finite temperature
/// or one below absolute zero (-273.15 degC).
SystematicFit fit_temperature(std::span<const double> rate_deg_h,
                              std::span<const double> temperature_c, double sample_rate_hz,
                              const SystematicOptions& options = {});

/// The same from the record's sums (`options.blocks` must be the record's
/// `blocks`, which sets the block means of the temperature span).
SystematicFit fit_temperature(const TemperatureRecord& record,
                              const SystematicOptions& options = {});

/// With the noise model fitted to the residual: standard errors, and (for
/// automatic degree) the degree chosen and the coefficients refitted.
SystematicFit finish_temperature_fit(const SystematicFit& first, std::span<const double> rate_deg_h,
                                     std::span<const double> temperature_c, double sample_rate_hz,
                                     const NoiseModel& noise,
                                     const SystematicOptions& options = {});

/// For automatic degree, the degree chosen with the noise model of the
/// residual and the coefficients refitted (a forced degree is kept); the
/// standard errors are left to set_standard_errors(), with the noise model of
/// the final residual. finish_temperature_fit() is this and
/// set_standard_errors() under `noise`.
SystematicFit choose_temperature_degree(const SystematicFit& first, const TemperatureRecord& record,
                                        const NoiseModel& noise,
                                        const SystematicOptions& options = {});

/// Sets fit.standard_errors from the coefficients' covariance under `noise`
/// (coefficient_covariance(), from the record's sums; fit.t_ref_c must be
/// the record's).
void set_standard_errors(SystematicFit& fit, const TemperatureRecord& record,
                         const NoiseModel& noise);

/// Beside a forced degree (the lab's quadratic), the criterion's verdict
/// under `noise` (the final residual's model): fit.criterion and
/// fit.criterion_degree from degree 0 up, the degree and coefficients
/// untouched. Nothing for a chosen degree (it has them) or a
/// constant fallback.
void set_criterion_verdict(SystematicFit& fit, const TemperatureRecord& record,
                           const NoiseModel& noise, const SystematicOptions& options = {});

/// Subtracts the fitted polynomial from `rate_deg_h` in place.
void subtract_temperature_fit(const SystematicFit& fit, std::span<double> rate_deg_h,
                              std::span<const double> temperature_c);

/// The fitted polynomial at every temperature sample [deg/h].
std::vector<double> temperature_law(const SystematicFit& fit,
                                    std::span<const double> temperature_c);

/// The residual rate_deg_h minus the fitted polynomial as a new vector, with
/// room for one more sample (the Allan deviation's angle record).
std::vector<double> temperature_fit_residual(const SystematicFit& fit,
                                             std::span<const double> rate_deg_h,
                                             std::span<const double> temperature_c);

/// The factors by which subtracting a least-squares polynomial of `degree`
/// in temperature changes each noise term's expected overlapping Allan
/// variance at `tau_s` (for noise_fit.h). With P the projection on the
/// polynomial columns, A the Allan variance's quadratic form and Sigma a
/// term's covariance, E[AVAR of the residual] = tr(A (I-P) Sigma (I-P)) and
/// the factor is that over tr(A Sigma); computed on `blocks` block means
/// (taus shorter than a block scale the first block's correction linearly;
/// the rate ramp R is deterministic: the ratio of the residual's AVAR to the
/// ramp's). Gauss-Markov: on a grid of Tc, 8 per decade, from tau_s.front()/2
/// to 30 tau_s.back().
DetrendFactors detrend_factors(std::span<const double> temperature_c, double sample_rate_hz,
                               double t_ref_c, int degree, std::span<const double> tau_s,
                               int blocks = 1024);

/// The same from the record's sums (blocks: the record's `detrend_blocks`;
/// t_ref_c: the record's).
DetrendFactors detrend_factors(const TemperatureRecord& record, int degree,
                               std::span<const double> tau_s);

/// The covariance (row-major, (d+1)^2) of least-squares coefficients of the
/// columns (T - t_ref)^j, j = 0..degree, under the noise model (exposed for
/// tests).
std::vector<double> coefficient_covariance(std::span<const double> temperature_c,
                                           double sample_rate_hz, double t_ref_c, int degree,
                                           const NoiseModel& noise, int blocks = 1024);

}  // namespace foglab::model
