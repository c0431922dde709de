// foglab — scale-factor calibration on a rate table: the lab manual's output model (eq. 10,
// section 2.1) fitted to a run's plateaus.
//
//   u(w, T) = S(T) [1 + f(w)] w + u0(T)        (core/output_model.h, which sim/rate_table.h
//                                               generates from)
//   S(T)  = S (1 + sum_k s_k dT^k),  f(w) = sum_k a_k w^k + (A/2) sign(w),
//   u0(T) = u0 + sum_k b_k dT^k,     dT = T - T_ref
//
// Each plateau (a run of samples with one commanded rate, its first settle_s left out) gives
// one point: the mean output and the mean temperature at its rate. The model is fitted to
// those points by least squares (Gauss-Newton from the linearised model) in two passes:
//   1. every plateau weighted alike (ordinary least squares);
//   2. the samples less that fit, joined into one rate record, give their Allan deviation
//      and the noise model fitted to it (model/noise_fit.h), the wander terms (flicker,
//      random walk) taken one standard error above their estimates; the model gives the
//      covariance V of the plateau means (Greenhall's structure function,
//      core/noise_model.h), and the fit is repeated with weights V^-1 (generalised least
//      squares). A slow bias wander correlates the plateaus of one temperature block;
//      weighting them alike would take it for a temperature law and state intervals too
//      narrow for it.
// The covariance is (J^T V^-1 J)^-1 times max(1, chi^2 / dof) of the residuals (V = the
// identity and the residual variance when no noise model could be fitted: a note says so);
// the intervals are Student's t with the residual degrees of freedom.
//
// Nonlinearity, two definitions:
//   * IEEE Std 952-1997 (scale-factor nonlinearity): the largest deviation of the fitted
//     input-output curve at T_ref from its least-squares straight line over [-FS, FS] (the
//     continuous fit, on a fine uniform grid), as a fraction of the full-scale output S FS
//     [ppm of full scale];
//   * the lab manual (lab 1, its step 3.5): (largest - smallest) / mean of the plateaus' scale
//     factors (u - u_rest) / w at the temperature nearest T_ref [%], u_rest the zero-rate
//     plateaus' mean output there (the fitted u0(T) when the run has none).
// The inverse (eq. 11), for correcting an output: w = (u - u0(T)) / (S(T) [1 + f(w)]).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "foglab/core/language.h"
#include "foglab/core/noise_model.h"

namespace foglab::model {

/// A rate-table run as recorded: one row a sample.
struct CalibrationRecord {
  double sample_rate_hz = 0.0;
  std::span<const double> rate_command_deg_s;  ///< [deg/s] the commanded table rate
  std::span<const double> output_lsb;          ///< [LSB] the gyro's output u
  std::span<const double> temperature_c;       ///< [degC]; empty: one unknown temperature
};

/// Where the plateaus are found.
enum class PlateauSource {
  commanded_rate,  ///< runs of one value of the rate column (the commanded rate)
  /// Runs where the output stays level (steps between 1 s block means below 8 robust standard
  /// deviations of those steps): for a rate column that is a measured rate (an encoder's),
  /// never constant; each plateau's rate is then the rate column's mean over it.
  output,
};

struct CalibrationOptions {
  PlateauSource plateaus = PlateauSource::commanded_rate;
  double settle_s = 5.0;      ///< [s] left out at each plateau's start
  double reference_c = 25.0;  ///< [degC] T_ref of the temperature polynomials
  /// Degrees of the temperature polynomials of the bias and the scale factor; -1: as many
  /// as the distinct temperatures allow (one less than their number), at most 2.
  int bias_temperature_degree = -1;
  int scale_factor_temperature_degree = -1;
  /// Terms a_1 .. a_d of f(w); -1: chosen from the data (calibrate(): the highest term kept
  /// only while the plateaus show it, t above the 99.5 % point, up to degree 5).
  int nonlinearity_degree = -1;
  bool asymmetry = true;  ///< fit A (needs positive and negative rates)
  /// Weight the plateaus by their means' covariance from the noise model identified on the
  /// run's residual record (generalised least squares; header); false: all alike (ordinary
  /// least squares, the residual variance taken as white).
  bool noise_covariance = true;
  /// When not empty, S(T)'s polynomial is these s_1, s_2, ... [1/degC^k], known, not fitted:
  /// a triad's cross-axis fit takes the gyro's own (calibrate_triad()).
  std::vector<double> known_scale_factor_temp;
  /// [LSB/(deg/s)] what turns the output into a rate for the noise model and N; 0: the fitted
  /// S (a cross-axis fit's S is the misalignment's small share of it).
  double rate_unit_lsb_per_deg_s = 0.0;
};

/// One plateau's point.
struct CalibrationPlateau {
  double rate_deg_s = 0.0;        ///< [deg/s] commanded
  std::int64_t first_sample = 0;  ///< the first sample used (after the settle time)
  std::int64_t samples = 0;       ///< samples used
  double output_mean_lsb = 0.0;   ///< [LSB]
  double output_sd_lsb = 0.0;     ///< [LSB] standard deviation of the samples
  double temperature_c = 0.0;     ///< [degC] mean
  double residual_lsb = 0.0;      ///< [LSB] output mean minus the fitted model
};

/// A fitted coefficient with its standard error and 95 % interval.
struct CalibratedValue {
  double value = 0.0;
  double sd = 0.0;
  double ci95_low = 0.0;
  double ci95_high = 0.0;
};

/// The error budget of eq. (13) at full scale, rate-equivalent [deg/h]: what each calibrated
/// term's 95 % uncertainty, and the noise, leave in a corrected rate.
struct CalibrationBudget {
  double bias_deg_h = 0.0;          ///< the bias's 95 % half-width
  double scale_factor_deg_h = 0.0;  ///< the scale factor's 95 % half-width times FS
  double nonlinearity_deg_h = 0.0;  ///< the largest plateau residual, as a rate
  double noise_1s_deg_h = 0.0;      ///< the white noise averaged over 1 s: N / sqrt(1 s)
};

struct Calibration {
  std::vector<CalibrationPlateau> plateaus;
  double reference_c = 25.0;           ///< [degC]
  double full_scale_deg_s = 0.0;       ///< [deg/s] the largest |rate| of the run
  std::vector<double> temperatures_c;  ///< the distinct plateau temperatures (0.5 degC apart)
  CalibratedValue scale_factor;        ///< S [LSB/(deg/s)] at T_ref
  std::vector<CalibratedValue> scale_factor_temp;  ///< s_k [1/degC^k]
  CalibratedValue bias;                            ///< u0 [LSB] at T_ref
  std::vector<CalibratedValue> bias_temp;          ///< b_k [LSB/degC^k]
  std::vector<CalibratedValue> nonlinearity;       ///< a_k [1/(deg/s)^k]
  int nonlinearity_degree = 0;                     ///< d of a_1 .. a_d, as fitted
  CalibratedValue asymmetry;                       ///< A; NaN when not fitted
  CalibratedValue bias_deg_h;                      ///< u0 / S as a rate [deg/h]
  double nonlinearity_ieee_ppm_fs = 0.0;           ///< [ppm of full scale] IEEE Std 952 (header)
  double nonlinearity_lab1_percent = 0.0;  ///< [%] the lab manual's (header); NaN if < 2 rates
  double white_noise_deg_h_rt_hz = 0.0;    ///< N [deg/h/sqrt(Hz)] from the plateaus' samples
  double residual_rms_lsb = 0.0;           ///< [LSB] of the plateau residuals
  int dof = 0;                             ///< residual degrees of freedom
  /// The plateaus were weighted by the noise model's covariance (generalised least squares);
  /// false: alike (ordinary least squares), see `notes` for why when it was asked for.
  bool noise_covariance = false;
  NoiseModel noise;  ///< identified on the residual record [deg/h units]; zero without it
  /// The residuals' chi-square per degree of freedom in the fit's metric; the covariance is
  /// multiplied by it (by max(1, it) with the noise model's covariance).
  double dispersion = 1.0;
  CalibrationBudget budget;
  std::vector<Message> notes;
};

/// Finds the plateaus and fits the model. Throws DataError (too few plateaus for the model,
/// a plateau shorter than the settle time plus 10 samples is left out with a note, no
/// positive and negative rates for the asymmetry, mismatched columns) naming what is missing.
Calibration calibrate(const CalibrationRecord& record, const CalibrationOptions& options = {});

/// A triad's body axes' names, in order: gyro i's input axis, mounting j's table axis.
inline constexpr std::array<const char*, 3> kTriadAxes = {"x", "y", "z"};

/// One mounting of a triad on the rate table (sim/rate_table.h, RateTableTriad): the table
/// turned about body axis `table_axis`, the three gyros recorded side by side.
struct TriadRecord {
  double sample_rate_hz = 0.0;
  std::span<const double> rate_command_deg_s;         ///< [deg/s]
  std::array<std::span<const double>, 3> output_lsb;  ///< [LSB] gyros x, y, z
  std::span<const double> temperature_c;              ///< [degC]; empty: unknown
};

/// A triad's calibration: each gyro's eq. (10) from the mounting about its own axis, and the
/// misalignment M = I + m of its input axes from the others: gyro i's output on the mounting
/// about axis j (j != i) is u0_i(T) + S_i(T) m_ij w, fitted with S_i(T)'s temperature law
/// known from gyro i's own fit; m_ij = the fitted cross-axis scale factor / S_i [rad], its
/// variance by the delta method from both.
struct TriadCalibration {
  std::array<Calibration, 3> axes;
  /// m_ij [rad]: gyro i's sensitivity to a rate about body axis j; the diagonal is NaN.
  std::array<std::array<CalibratedValue, 3>, 3> misalignment_rad;
  /// The cross-axis fits, [i][j] for gyro i on the mounting about j (the diagonal unused).
  std::array<std::array<Calibration, 3>, 3> cross;
};

/// Calibrates a triad from its three mountings, `mountings[j]` with the table about axis j.
/// Throws as calibrate(), naming the gyro and the mounting.
TriadCalibration calibrate_triad(std::span<const TriadRecord, 3> mountings,
                                 const CalibrationOptions& options = {});

/// The model's output at rate w and temperature T [LSB].
double calibrated_output_lsb(const Calibration& c, double rate_deg_s, double temperature_c);

/// Eq. (11): the rate [deg/s] whose output is u at temperature T (the nonlinearity inverted
/// by fixed-point steps).
double corrected_rate_deg_s(const Calibration& c, double output_lsb, double temperature_c);

}  // namespace foglab::model
