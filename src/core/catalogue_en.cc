// foglab — the reports' English text (core/language.h).
#include "catalogue.h"

namespace foglab::detail {

namespace {

constexpr CatalogueEntry kEntries[] = {
    {Text::verbatim, "{}"},
    {Text::plots_skipped, "The plots were skipped: {}."},
    {Text::plot_skipped, "This plot was skipped: {}"},
    {Text::note, "Note: {}"},
    {Text::footer,
     "Written by foglab {}. Units: rate deg/h, time s, temperature degC; noise parameters as in "
     "IEEE Std 952 (N deg/h/sqrt(Hz), B deg/h, K deg/h/sqrt(s), R deg/h/s, Q deg/h*s); an "
     "accelerometer's in m/s^2 in place of deg/h."},
    {Text::value, "value"},
    {Text::interval95, "95 % interval"},
    {Text::unit, "unit"},
    {Text::cal_title, "foglab calibrate: {}"},
    {Text::cal_triad_title, "foglab calibrate, a triad: {}"},
    {Text::cal_section, "Calibration"},
    {Text::cal_run,
     "{} plateaus at {} temperature(s), full scale {} deg/s, T_ref {} degC. The manual's eq. "
     "(10): u = S (1 + sum s_k dT^k) [1 + sum a_k w^k + (A/2) sign(w)] w + u0 + sum b_k dT^k, "
     "dT = T - T_ref."},
    {Text::cal_coefficient, "coefficient"},
    {Text::cal_row_s, "S, scale factor at T_ref"},
    {Text::cal_row_sk, "s_{}, its temperature coefficient"},
    {Text::cal_row_ak, "a_{}, nonlinearity at full scale"},
    {Text::cal_row_a, "A, asymmetry (S+ - S-)/S"},
    {Text::cal_row_u0, "u0, bias at T_ref"},
    {Text::cal_row_u0_rate, "u0 as a rate"},
    {Text::cal_row_bk, "b_{}, its temperature coefficient"},
    {Text::unit_lsb_per_deg_s, "LSB/(deg/s)"},
    {Text::unit_ppm_per_degc_k, "ppm/degC^{}"},
    {Text::unit_ppm_fs, "ppm of full scale"},
    {Text::unit_ppm, "ppm"},
    {Text::unit_lsb, "LSB"},
    {Text::unit_deg_h, "deg/h"},
    {Text::unit_lsb_per_degc_k, "LSB/degC^{}"},
    {Text::cal_nonlinearity,
     "Nonlinearity: {} ppm of full scale (IEEE Std 952: the fitted curve's largest deviation "
     "from its straight line), {} % (the lab manual's spread of the plateaus' scale factors); "
     "f(w) of degree {}."},
    {Text::cal_noise,
     "Noise: N = {} deg/h/sqrt(Hz) from the plateaus' samples (ARW {} deg/sqrt(h)); plateau "
     "residuals {} LSB rms, {} degrees of freedom."},
    {Text::cal_weighting_noise,
     "Weighting: the plateau means' covariance from the residual record's noise (N {} "
     "deg/h/sqrt(Hz), B {} deg/h, K {} deg/h/sqrt(s), Gauss-Markov {} deg/h over {} s); "
     "chi-square per degree of freedom {}."},
    {Text::cal_weighting_alike, "Weighting: every plateau alike (ordinary least squares)."},
    {Text::cal_budget, "Error budget at full scale (eq. 13, 95 %):"},
    {Text::cal_budget_bias, "bias [deg/h]"},
    {Text::cal_budget_scale_factor, "scale factor [deg/h]"},
    {Text::cal_budget_nonlinearity, "nonlinearity residual [deg/h]"},
    {Text::cal_budget_noise, "noise over 1 s [deg/h]"},
    {Text::cal_corrected_rate, "Corrected rate (eq. 11):"},
    {Text::cal_equation,
     "w [deg/s] = (u - ({:.9g}{})) / ({:.10g} (1{}) (1{})),  dT = T - {:g} degC (the "
     "nonlinearity's w: one or two fixed-point steps)"},
    {Text::symbol_rate, "w"},
    {Text::symbol_dt, "dT"},
    {Text::cal_plateaus, "The plateaus"},
    {Text::cal_col_rate, "rate [deg/s]"},
    {Text::cal_col_samples, "samples"},
    {Text::cal_col_mean, "mean output [LSB]"},
    {Text::cal_col_sd, "sd [LSB]"},
    {Text::cal_col_temperature, "temperature [degC]"},
    {Text::cal_col_residual, "residual [LSB]"},
    {Text::cal_fig_output,
     "The plateaus' mean output against the table's rate, with the fitted eq. (10)"},
    {Text::cal_fig_scale_factor,
     "The plateaus' scale factors (u - u_rest) / w against rate, with the fitted S(T) [1 + "
     "f(w)]: the nonlinearity"},
    {Text::cal_fig_residual_rate, "The plateau residuals against rate"},
    {Text::cal_fig_residual_temperature, "The plateau residuals against temperature"},
    {Text::cal_plot_output, "Output against rate"},
    {Text::cal_plot_scale_factor, "Scale factor against rate"},
    {Text::cal_plot_residual_rate, "Residuals against rate"},
    {Text::cal_plot_residual_temperature, "Residuals against temperature"},
    {Text::cal_axis_rate, "table rate [deg/s]"},
    {Text::cal_axis_output, "output [LSB]"},
    {Text::cal_axis_scale_factor, "scale factor (u - u_rest) / w [LSB/(deg/s)]"},
    {Text::cal_axis_residual, "plateau residual [LSB]"},
    {Text::cal_axis_temperature, "temperature [degC]"},
    {Text::cal_legend_temperature, "{:.1f} degC"},
    {Text::cal_legend_plateaus, "plateaus"},
    {Text::cal_misalignment, "Misalignment"},
    {Text::cal_misalignment_text,
     "m_ij [mrad]: gyro i's sensitivity to a rate about body axis j, M = I + m (small angles), "
     "with 95 % intervals."},
    {Text::cal_gyro, "gyro"},
    {Text::cal_own_axis, "1 (scale factor)"},
    {Text::cal_gyro_section, "Gyro {} ('{}')"},
    {Text::cal_gyro_plot, "gyro {}: {}"},
    {Text::cal_gyro_figure, "Gyro {}: {}"},
    // ---- lab 1's report ----
    // ---- lab 2's report ----
    // ---- analyze's report ----
    // ---- the analyses' notes ----
};

}  // namespace

std::span<const CatalogueEntry> catalogue_en() { return kEntries; }

}  // namespace foglab::detail
