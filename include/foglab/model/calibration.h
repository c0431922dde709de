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
// those points by least squares (Gauss-Newton from the linearised model), with every plateau
// weighted alike: a plateau's mean carries the white noise and the slow bias wander alike, and
// the residuals measure both. The covariance is the residual variance times (J^T J)^-1, the
// intervals Student's t with the residual degrees of freedom.
//
// Nonlinearity, two definitions:
//   * IEEE Std 952-1997 (scale-factor nonlinearity): the largest deviation of the fitted
//     input-output curve at T_ref from its least-squares straight line over [-FS, FS] (the
//     continuous fit, on a fine uniform grid), as a fraction of the full-scale output S FS
//     [ppm of full scale];
//   * the lab manual (lab 1, its step 3.5): (largest - smallest) / mean of the plateaus' scale
//     factors (u - u0(T)) / w at the temperature nearest T_ref [%].
// The inverse (eq. 11), for correcting an output: w = (u - u0(T)) / (S(T) [1 + f(w)]).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace foglab::model {

/// A rate-table run as recorded: one row a sample.
struct CalibrationRecord {
  double sample_rate_hz = 0.0;
  std::span<const double> rate_command_deg_s;  ///< [deg/s] the commanded table rate
  std::span<const double> output_lsb;          ///< [LSB] the gyro's output u
  std::span<const double> temperature_c;       ///< [degC]; empty: one unknown temperature
};

struct CalibrationOptions {
  double settle_s = 5.0;      ///< [s] left out at each plateau's start
  double reference_c = 25.0;  ///< [degC] T_ref of the temperature polynomials
  /// Degrees of the temperature polynomials of the bias and the scale factor; -1: as many
  /// as the distinct temperatures allow (one less than their number), at most 2.
  int bias_temperature_degree = -1;
  int scale_factor_temperature_degree = -1;
  int nonlinearity_degree = 2;  ///< terms a_1 .. a_d of f(w)
  bool asymmetry = true;        ///< fit A (needs positive and negative rates)
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
  CalibratedValue asymmetry;                       ///< A; NaN when not fitted
  CalibratedValue bias_deg_h;                      ///< u0 / S as a rate [deg/h]
  double nonlinearity_ieee_ppm_fs = 0.0;           ///< [ppm of full scale] IEEE Std 952 (header)
  double nonlinearity_lab1_percent = 0.0;  ///< [%] the lab manual's (header); NaN if < 2 rates
  double white_noise_deg_h_rt_hz = 0.0;    ///< N [deg/h/sqrt(Hz)] from the plateaus' samples
  double residual_rms_lsb = 0.0;           ///< [LSB] of the plateau residuals
  int dof = 0;                             ///< residual degrees of freedom
  CalibrationBudget budget;
  std::vector<std::string> notes;
};

/// Finds the plateaus and fits the model. Throws DataError (too few plateaus for the model,
/// a plateau shorter than the settle time plus 10 samples is left out with a note, no
/// positive and negative rates for the asymmetry, mismatched columns) naming what is missing.
Calibration calibrate(const CalibrationRecord& record, const CalibrationOptions& options = {});

/// The model's output at rate w and temperature T [LSB].
double calibrated_output_lsb(const Calibration& c, double rate_deg_s, double temperature_c);

/// Eq. (11): the rate [deg/s] whose output is u at temperature T (the nonlinearity inverted
/// by fixed-point steps).
double corrected_rate_deg_s(const Calibration& c, double output_lsb, double temperature_c);

}  // namespace foglab::model
