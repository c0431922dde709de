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
    {Text::unit_percent, "%"},
    {Text::unit_lsb, "LSB"},
    {Text::unit_deg_h, "deg/h"},
    {Text::unit_lsb_per_degc_k, "LSB/degC^{}"},
    {Text::unit_deg_h_per_degc, "deg/h/degC"},
    {Text::unit_deg_h_per_degc_k, "deg/h/degC^{}"},
    {Text::unit_s, "s"},
    {Text::unit_hz, "Hz"},
    {Text::unit_deg_sqrt_h, "deg/sqrt(h)"},
    {Text::unit_deg_h_sqrt_hz, "deg/h/sqrt(Hz)"},
    {Text::unit_deg_h_sqrt_s, "deg/h/sqrt(s)"},
    {Text::unit_deg_h_s, "deg/h/s"},
    {Text::unit_deg_h_times_s, "deg/h*s"},
    {Text::unit_m_s_sqrt_h, "m/s/sqrt(h)"},
    {Text::unit_deg_s, "deg/s"},
    {Text::unit_rad_s, "rad/s"},
    {Text::unit_m_s2, "m/s^2"},
    {Text::unit_mg, "mg"},
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
    {Text::lab1_title, "foglab lab 1: variant {}"},
    {Text::lab1_modulation_none, "no modulation"},
    {Text::lab1_modulation_square, "square modulation"},
    {Text::lab1_modulation_sine, "sine modulation"},
    {Text::lab1_plot_intensity,
     "Intensity at the detector against the total phase (I vs fi), rate ramp over "
     "+-Omega_pi/2"},
    {Text::lab1_plot_output, "Demodulated output against rate (S vs Om), open loop"},
    {Text::lab1_plot_trace_square,
     "Square modulation at a constant rate: detector and phase difference"},
    {Text::lab1_plot_trace_sine,
     "Sine modulation at a constant rate: detector and phase difference"},
    {Text::lab1_plot_ramp_time, "Open loop over the rate ramp: output and rate against time"},
    {Text::lab1_plot_sweep, "The lab's sweep: scale factor against rate"},
    {Text::lab1_plot_closed_ramp, "Rate ramp beyond Omega_pi/2: closed loop against open loop"},
    {Text::lab1_plot_closed_trace,
     "Closed loop at {:.4g} deg/s ({:.2g} Omega_pi/2): the feedback phase and the output"},
    {Text::lab1_plot_off_frequency, "Square modulation at {:.3g} f_m: transition spikes"},
    {Text::lab1_axis_total_phase, "total phase phi_s + dphi_m [rad]"},
    {Text::lab1_axis_detector, "detector output [a.u.]"},
    {Text::lab1_axis_input_rate, "input rate [deg/s]"},
    {Text::lab1_axis_output_mean, "output [a.u.] (no modulation: the detector's mean)"},
    {Text::lab1_axis_time_us, "time [us]"},
    {Text::lab1_axis_modulation_phase, "phase difference dphi_m [rad]"},
    {Text::lab1_axis_time_ms, "time [ms]"},
    {Text::lab1_axis_output_lowpassed, "demodulated output, low-passed [a.u.]"},
    {Text::lab1_axis_open_scale_factor, "open-loop scale factor S/Omega [a.u. per deg/s]"},
    {Text::lab1_axis_closed_scale_factor, "closed-loop scale factor [1]"},
    {Text::lab1_axis_closed_output, "closed-loop output [deg/s]"},
    {Text::lab1_axis_open_output, "open-loop output S [a.u.]"},
    {Text::lab1_axis_feedback_phase, "feedback phase psi [rad]"},
    {Text::lab1_legend_cosine, "gamma (1 + cos phi)"},
    {Text::lab1_legend_time_simulation, "{}, time simulation"},
    {Text::lab1_legend_steady_state, "analytic steady state"},
    {Text::lab1_legend_detector, "detector"},
    {Text::lab1_legend_modulation_phase, "modulation phase difference (right axis)"},
    {Text::lab1_legend_input_rate, "input rate (right axis)"},
    {Text::lab1_legend_square_analytic, "square, analytic"},
    {Text::lab1_legend_square_time, "square, time simulation"},
    {Text::lab1_legend_sine_time, "sine, time simulation"},
    {Text::lab1_legend_closed_right, "closed loop (right axis)"},
    {Text::lab1_legend_ideal, "output = input"},
    {Text::lab1_legend_closed, "closed loop"},
    {Text::lab1_legend_open_square_right, "open loop, square (right axis)"},
    {Text::lab1_legend_range_edge, "+Omega_pi/2"},
    {Text::lab1_legend_feedback_phase, "phase ramp psi (right axis)"},
    {Text::lab1_legend_closed_output, "output -u/K_s"},
    {Text::lab1_fig_intensity,
     "Intensity at the detector against the total phase (items 2.5, 2.7, 2.9)."},
    {Text::lab1_fig_output,
     "Demodulated output against the input rate, each modulation (items 2.7, 2.9)."},
    {Text::lab1_fig_trace_square, "Time traces, square modulation at 0.5 Omega_pi/2."},
    {Text::lab1_fig_trace_sine, "Time traces, sine modulation at 0.5 Omega_pi/2."},
    {Text::lab1_fig_ramp_time, "The open loop over the rate ramp against time."},
    {Text::lab1_fig_sweep, "Scale factors of the ten-rate sweeps (items 3.4, 5.3)."},
    {Text::lab1_fig_closed_ramp,
     "The closed loop follows a ramp well beyond Omega_pi/2; the open loop folds (item 4.2)."},
    {Text::lab1_fig_closed_trace_inside,
     "The closed loop at a constant rate inside the open loop's range, from u = 0: the phase "
     "ramp psi steps by u every transit time and is reset by 2 pi whenever it leaves [0, 2 pi) "
     "(the manual's Fig. 11); the output -u/K_s settles to the rate (item 4.2)."},
    {Text::lab1_fig_closed_trace_beyond,
     "The same beyond the open loop's range (phi_s past pi/2, where the open loop folds): the "
     "steps are larger and psi resets more often; the output still settles to the rate."},
    {Text::lab1_fig_off_frequency, "Square modulation away from the proper frequency."},
    {Text::title_university, "ITMO University"},
    {Text::title_lab, "Lab work {}: {}"},
    {Text::title_lab1_name, "Linearity of the output signal of a fibre-optic gyroscope"},
    {Text::title_lab2_name,
     "Identification of the error-model components of a fibre-optic gyroscope's output "
     "signal"},
    {Text::title_variant, "Variant {}"},
    {Text::title_student, "Student: {}"},
    {Text::title_group, "Group: {}"},
    {Text::title_date, "Date: {}"},
    {Text::title_aim_heading, "Aim of the work"},
    {Text::title_aim_lab1,
     "To study how phase modulation makes a fibre-optic gyroscope sensitive to small rates, "
     "in the open-loop scheme and in the closed loop with a phase ramp, and to measure how "
     "linear the output characteristic of each scheme is; here on foglab's model of the "
     "optical signal chain in place of the Simulink models."},
    {Text::title_aim_lab2,
     "To identify the components of the error model of two fibre-optic gyroscopes of "
     "different accuracy classes from their static output, at constant temperature and "
     "during a 10 degC change, by the power spectral density and the Allan variance, and to "
     "compare their values and the accuracy classes they give."},
    {Text::lab1_coil, "The coil (item 1.1)"},
    {Text::lab1_open_loop, "Open loop: no, square and sine modulation (items 2.4-2.10)"},
    {Text::lab1_square_sweep, "Open loop, square modulation: the ten-rate sweep (items 3.1-3.6)"},
    {Text::lab1_sine_sweep, "Open loop, sine modulation (phi_m = 1.8 rad): the sweep"},
    {Text::lab1_closed_loop, "Closed loop: the ramp and the ten-rate sweep (items 4.2, 5.1-5.4)"},
    {Text::lab1_checks, "Checks against theory"},
    {Text::lab1_conclusions, "Conclusions"},
    {Text::lab1_quantity, "quantity"},
    {Text::lab1_row_length, "fibre length L"},
    {Text::lab1_row_radius, "coil radius R"},
    {Text::lab1_row_wavelength, "wavelength lambda"},
    {Text::lab1_row_group_index, "group index n_g"},
    {Text::lab1_row_scale_factor, "Sagnac scale factor K_s = 4 pi R L / (lambda c)"},
    {Text::lab1_row_range, "range Omega_pi/2 = (pi/2) / K_s"},
    {Text::lab1_row_range_deg, "range Omega_pi/2"},
    {Text::lab1_row_transit_time, "transit time tau0 = n_g L / c"},
    {Text::lab1_row_modulation_frequency, "modulation frequency f_m = 1/(2 tau0)"},
    {Text::lab1_unit_m, "m"},
    {Text::lab1_unit_nm, "nm"},
    {Text::lab1_unit_scale_factor, "s (rad per rad/s)"},
    {Text::lab1_unit_us, "us"},
    {Text::lab1_unit_khz, "kHz"},
    {Text::lab1_col_rate, "rate [deg/s]"},
    {Text::lab1_col_output_deg_s, "output [deg/s]"},
    {Text::lab1_col_scale_factor_1, "scale factor [1]"},
    {Text::lab1_col_s_time, "S, time [a.u.]"},
    {Text::lab1_col_s_analytic, "S, analytic [a.u.]"},
    {Text::lab1_col_sf_time, "SF, time [a.u. per deg/s]"},
    {Text::lab1_col_sf_analytic, "SF, analytic [a.u. per deg/s]"},
    {Text::lab1_col_s, "S [a.u.]"},
    {Text::lab1_col_sf, "SF [a.u. per deg/s]"},
    {Text::lab1_square_nonlinearity,
     "Nonlinearity over +-Omega_pi/2: {:.3f} % (time simulation), {:.3f} % (analytic, "
     "(sinc(pi/10) - sinc(pi/2)) / mean)."},
    {Text::lab1_range_30,
     "Range with 30 % nonlinearity (bisection to 0.1 %): +-{:.5g} deg/s = {:.4f} Omega_pi/2 "
     "(time simulation); analytic +-{:.5g} deg/s."},
    {Text::lab1_sine_nonlinearity, "Nonlinearity over +-Omega_pi/2: {:.3f} %."},
    {Text::lab1_closed_nonlinearity, "Nonlinearity over +-Omega_pi/2: {:.3g} ppm ({:.3g} %)."},
    {Text::lab1_check_square,
     "Square modulation: the time simulation follows S = 2 gamma sin(phi_s) within {:.2g} % of "
     "full scale at the sweep rates (goal 0.1 %)."},
    {Text::lab1_check_sine,
     "Sine modulation: it follows S = 2 gamma J1(phi_m) sin(phi_s) within {:.2g} % of full "
     "scale; J1(1.8) = {:.4f}."},
    {Text::lab1_check_closed,
     "Closed loop: {:.3g} ppm nonlinearity over +-Omega_pi/2; under the ramp to {:.4g} deg/s "
     "({:.3g} Omega_pi/2) the output stays on the input with a lag of {:.3g} deg/s at the end (a "
     "type-1 loop's ramp lag, theory {:.3g} deg/s), where the open loop has folded."},
    {Text::lab1_check_off_frequency,
     "Square modulation at {:.3g} f_m: the phase difference is 0 in {:.1f} % of the samples (the "
     "transition spikes; theory {:.1f} %) and the signal falls to {:.4f} of the proper one "
     "(theory, with the gate: {:.4f})."},
    {Text::lab1_conclusion_none,
     "Without modulation the detector gives gamma (1 + cos phi_s): flat at zero rate (no "
     "sensitivity to small rates) and blind to the sign of the rate."},
    {Text::lab1_conclusion_square,
     "Square modulation at f_m = {:.4g} kHz biases the interferometer to +-pi/2: the demodulated "
     "output 2 gamma sin(phi_s) is the steepest and odd in the rate; it needs exactly the proper "
     "frequency (off it: spikes and a loss of signal)."},
    {Text::lab1_conclusion_sine,
     "Sine modulation gives J1(phi_m) = {:.3f} of that at phi_m = 1.8 rad, with the same "
     "sine-shaped nonlinearity, and degrades gracefully off frequency."},
    {Text::lab1_conclusion_open,
     "Both open-loop outputs are sinusoidal in the rate: {:.1f} % nonlinearity over "
     "+-Omega_pi/2, 30 % reached at +-{:.4g} deg/s, and past Omega_pi/2 the output folds back, "
     "so the rate becomes ambiguous."},
    {Text::lab1_conclusion_closed,
     "The closed loop holds the interferometer at zero phase with the phase ramp and reads the "
     "rate from the feedback: linear ({:.2g} ppm) and not limited to Omega_pi/2."},
    // ---- lab 2's report ----
    {Text::lab2_constant_temperature, "constant temperature"},
    {Text::lab2_temperature_ramp, "temperature ramp"},
    {Text::lab2_run_title, "{}, {} ({}, {})"},
    {Text::lab2_title, "foglab lab 2: variant {}"},
    {Text::lab2_title_files, "foglab lab 2"},
    {Text::lab2_intro_generated,
     "Variant {} of the lab-2 data (seed {}), generated by foglab with a known truth: "
     "{}.{}"},
    {Text::lab2_intro_answer_key,
     " The answer key column holds the values the data were made with (computed from "
     "the model, not estimated)."},
    {Text::lab2_intro_files, "The lab's recordings {}."},
    {Text::lab2_intro_method,
     " Each run is analysed as the lab asks: the temperature polynomial is removed, "
     "then the PSD and the overlapping Allan deviation of the residual are read as the "
     "lab does (lines and minimum) and fitted with the IEEE Std 952 model (95 % "
     "intervals), the random bias is identified and the Table 1 class given."},
    {Text::lab2_not_visible, "not visible"},
    {Text::lab2_absent, "absent"},
    {Text::lab2_bi_at, "{} at {} s"},
    {Text::lab2_range_end, " (range end)"},
    {Text::lab2_process_wiener, "Wiener"},
    {Text::lab2_process_gauss_markov, "Gauss-Markov"},
    {Text::lab2_process_none, "not visible"},
    {Text::lab2_truth_both, "{} (constant) / {} (ramp)"},
    {Text::lab2_q_systematic_bias, "systematic bias"},
    {Text::lab2_m_lab_constant, "lab: constant term of polyfit(T, Y, 2)"},
    {Text::lab2_not_meaningful, " (not meaningful: T barely moves)"},
    {Text::lab2_m_at_mean_temperature, "fit: at the mean temperature"},
    {Text::lab2_at_temperature, " at {:.4g} degC"},
    {Text::lab2_q_c1, "temperature coefficient c1"},
    {Text::lab2_m_polynomial, "fit: polynomial in (T - mean)"},
    {Text::lab2_q_temperature_terms, "temperature terms that stand out"},
    {Text::lab2_m_criterion, "criterion: W_d + 6.63 d (1 % level)"},
    {Text::lab2_criterion_cell, "up to degree {}"},
    {Text::lab2_criterion_cell_none, "none at the 1 % level"},
    {Text::lab2_t_barely_moves, "- (T barely moves)"},
    {Text::lab2_degree_0_chosen, "- (degree 0 chosen)"},
    {Text::lab2_plus_minus, " +- {}"},
    {Text::lab2_q_random_bias, "random bias process"},
    {Text::lab2_m_model_choice, "fit: model choice"},
    {Text::lab2_q_k, "Wiener intensity K"},
    {Text::lab2_m_psd_k, "PSD: -2 slope at 1 Hz"},
    {Text::lab2_m_allan_k, "Allan: +1/2 line at 3 s"},
    {Text::lab2_m_fit, "fit [95 %]"},
    {Text::lab2_q_gm_sigma, "Gauss-Markov sigma"},
    {Text::lab2_q_gm_tc, "Gauss-Markov Tc"},
    {Text::lab2_q_n, "white noise N"},
    {Text::lab2_m_psd_n, "PSD: flat level"},
    {Text::lab2_m_allan_n, "Allan: -1/2 line at 1 s"},
    {Text::lab2_q_arw, "angle random walk"},
    {Text::lab2_m_arw, "fit: N/60"},
    {Text::lab2_q_bias_instability, "bias instability"},
    {Text::lab2_m_allan_minimum, "Allan: minimum [95 %]"},
    {Text::lab2_q_class, "accuracy class"},
    {Text::lab2_m_class, "Table 1: worse of BI and ARW"},
    {Text::lab2_class_cell, "{} ({})"},
    {Text::lab2_both_criteria, "both criteria"},
    {Text::lab2_by_arw, "by ARW"},
    {Text::lab2_by_bias_instability, "by bias instability"},
    {Text::lab2_change, "{}: {} -> {} {} ({:+.1f} %)"},
    {Text::lab2_change_changed, "; the 95 % intervals do not overlap: the ramp changed it."},
    {Text::lab2_change_unchanged,
     "; the 95 % intervals overlap: unchanged within the uncertainty."},
    {Text::lab2_change_not_comparable, "."},
    {Text::lab2_temperature_spans,
     "Temperature: the ramp run spans {:.3g} degC (the constant run {:.2g} degC). "},
    {Text::lab2_polynomial_moves,
     "Its fitted polynomial (degree {}) moves the bias by {} deg/h over the ramp, "
     "{:.3g} times the bias instability: without removing it the ramp would pass for a "
     "large drift and spoil the Allan deviation at long tau."},
    {Text::lab2_no_dependence,
     "No temperature polynomial was removed from it (degree 0): whatever the temperature did "
     "stays in the record."},
    {Text::lab2_verdict_term, "c{} = {} +- {} {} ({:.1f} standard errors{}); "},
    {Text::lab2_verdict_stands_out, ": stands out of the noise"},
    {Text::lab2_verdict_in_noise, ", below the criterion's {:.3g}"},
    {Text::lab2_verdict_degree,
     "the criterion (W_d + {:.3g} d: a term must stand out at the 1 % level) would keep "
     "degree {}."},
    {Text::lab2_verdict_nothing_stands_out,
     " No temperature term reaches the criterion's 1 % level in this run: the slope is not "
     "separated from the random bias with that confidence, which does not show that there is "
     "no dependence (its 95 % interval above is what the run allows)."},
    {Text::lab2_bias_at_mean,
     "Systematic bias at the mean temperature: {:.5g} deg/h (constant, {:.4g} degC) "
     "and {:.5g} deg/h (ramp, {:.4g} degC), {} deg/h apart"},
    {Text::lab2_bias_wander,
     " — {:.2g} times the fitted model's Allan deviation at half the record ({} "
     "deg/h), the scale on which the random bias moves the mean of a record"},
    {Text::lab2_bias_end, "."},
    {Text::lab2_bias_constant_not_meaningful,
     "; at constant temperature the lab's polyfit constant term is not meaningful (the "
     "temperature moves too little to extrapolate to 0 degC), so compare these."},
    {Text::lab2_random_bias_differs,
     "Random bias: {} at constant temperature, {} during the ramp. Over a record this "
     "short a Gauss-Markov process whose correlation time is near the end of the tau "
     "range looks like a random walk, so the two answers can differ on the same gyro; "
     "the run whose Allan deviation reaches further past the hump decides."},
    {Text::lab2_random_bias_both, "Random bias: {} in both runs"},
    {Text::lab2_random_bias_gm, "; sigma {} -> {} deg/h, Tc {} -> {} s."},
    {Text::lab2_k_symbol, "K"},
    {Text::lab2_white_noise_fit, "White noise N (fit)"},
    {Text::lab2_bias_instability_minimum, "Bias instability (ADEV minimum)"},
    {Text::lab2_only_one_run, "Only the {} run resolves {} = {} {}{}."},
    {Text::lab2_run_ramp, "ramp"},
    {Text::lab2_run_constant, "constant"},
    {Text::lab2_ramp_not_removed,
     ": a drift the temperature polynomial does not remove (e.g. a dependence on the "
     "rate of temperature change)"},
    {Text::lab2_class_same, "Accuracy class: {} in both runs."},
    {Text::lab2_class_differs, "Accuracy class: {} at constant temperature, {} during the ramp."},
    {Text::lab2_conclusion_unchanged,
     "Conclusion: once the temperature polynomial is removed, the ramp leaves the "
     "random error unchanged within the 95 % intervals: the temperature acts on the "
     "systematic part, which the polynomial captures."},
    {Text::lab2_conclusion_changed,
     "Conclusion: the ramp changed {}, beyond what the polynomial removes; check the "
     "residual's Allan deviation at long tau and the bias-temperature plot for "
     "hysteresis."},
    {Text::lab2_and, " and "},
    {Text::lab2_changed_white, "the white noise"},
    {Text::lab2_changed_bias_instability, "the bias instability"},
    {Text::lab2_changed_k, "the Wiener intensity"},
    {Text::lab2_changed_process, "the random-bias answer"},
    {Text::lab2_changed_term, "the {} term"},
    {Text::lab2_class_run, "{} {} ({})"},
    {Text::lab2_class_at_constant, "at constant temperature"},
    {Text::lab2_class_during_ramp, "during the temperature ramp"},
    {Text::lab2_class_agree, "both criteria agree"},
    {Text::lab2_class_decided_arw, "decided by the ARW"},
    {Text::lab2_class_decided_bi, "decided by the bias instability"},
    {Text::lab2_col_quantity, "quantity"},
    {Text::lab2_col_method, "method"},
    {Text::lab2_col_answer_key, "answer key"},
    {Text::lab2_table_heading, "{}{}: the lab's table"},
    {Text::lab2_accuracy_class_line, "Accuracy class — {}."},
    {Text::lab2_scale_factor_note,
     "Table 1 also grades the scale factor's stability; a static record (zero rate) cannot "
     "measure it: run the gyro on a rate table and give the runs to `foglab calibrate` "
     "(eq. 10: the scale factor, its temperature dependence and nonlinearity)."},
    {Text::lab2_ramp_changed, "What the temperature ramp changed"},
    {Text::lab1_plot_closed_ramp_time,
     "Closed loop over the rate ramp: rate and output against time (item 4.2)"},
    {Text::lab1_axis_feedback_step, "feedback phase step u [rad]"},
    {Text::lab1_legend_rate, "input rate"},
    {Text::lab1_legend_feedback_step, "u, the manual's output (right axis)"},
    {Text::lab1_fig_closed_ramp_time,
     "Item 4.2's figure (rate and output signal): the rate ramps to 3 Omega_pi/2, far past the "
     "open loop's range (red), and the closed loop's output follows it, as the rate -u/K_s "
     "(foglab's output, left axis) and as the feedback phase step u = -K_s Omega (the manual's, "
     "right axis, which runs downwards)."},
    {Text::lab1_col_feedback_phase_rad, "output: feedback phase step u [rad]"},
    {Text::lab1_col_scale_factor_s, "scale factor u/Omega [s]"},
    {Text::lab1_phase_convention,
     "The manual reads the closed loop's output as the feedback phase step u (items 4.2, 5.2): "
     "its scale factor is then -K_s, {:.6g} s over this sweep (-K_s = {:.6g} s from the coil). "
     "foglab's output is the rate -u/K_s, scale factor 1; its phase output gives this table in "
     "the manual's form. The nonlinearity is the same in both forms, since the factor -K_s "
     "cancels in (max - min)/mean: {:.3g} ppm (phase) and {:.3g} ppm (rate), apart only by the "
     "arithmetic's rounding. See docs/manual_notes.md."},
    {Text::lab1_phase_convention_shown,
     "This table is in the manual's form (the phase output): the output is the feedback phase "
     "step u (items 4.2, 5.2), its scale factor -K_s, {:.6g} s over this sweep (-K_s = {:.6g} s "
     "from the coil). foglab's default is the rate -u/K_s, scale factor 1. The nonlinearity is "
     "the same in both forms, since the factor -K_s cancels in (max - min)/mean: {:.3g} ppm "
     "(phase) and {:.3g} ppm (rate), apart only by the arithmetic's rounding. See "
     "docs/manual_notes.md."},
    {Text::lab2_k_convention,
     "K read the manual's way (docs/manual_notes.md): the +1/2 line read at tau = 1 s gives "
     "K/sqrt(3) = {} (constant) and {} (ramp); the -2 line's level at 1 Hz gives K/(2 pi) = {} "
     "and {} deg/h/sqrt(s). The table reads the +1/2 line at tau = 3 s, where it equals K (eq. "
     "20: K^2 tau/3), and the PSD line as K^2/(2 pi f)^2."},
    {Text::lab2_gyros_heading, "{} against {}"},
    {Text::lab2_gyros_value,
     "{} at constant temperature: {} {}, {} {} {} — {}'s is {:.3g} times {}'s"},
    {Text::lab2_gyros_apart, "; the 95 % intervals do not overlap."},
    {Text::lab2_gyros_overlap,
     "; the 95 % intervals overlap: this record does not tell them apart."},
    {Text::lab2_gyros_process, "Random bias at constant temperature: {} in {}, {} in {}."},
    {Text::lab2_gyros_class, "Accuracy class at constant temperature (Table 1): {} {}, {} {}."},
    {Text::lab2_question_18,
     "Review question 18: how does temperature affect the output of a FOG?"},
    {Text::lab2_answer_slope,
     "over the ramp's {:.3g} degC its bias follows c1 = {} +- {} deg/h/degC ({:.1f} standard "
     "errors{}); the fitted polynomial moves the bias by {} deg/h, {:.3g} times its bias "
     "instability."},
    {Text::lab2_answer_stands_out, ", out of the noise at the 1 % level"},
    {Text::lab2_answer_not_separated, ", not separated from the random bias at the 1 % level"},
    {Text::lab2_answer_no_slope, "its ramp run shows no temperature slope."},
    {Text::lab2_answer_noise_unchanged,
     " Its noise terms are unchanged within the 95 % intervals."},
    {Text::lab2_answer_noise_changed, " The ramp also changed {} beyond the uncertainty."},
    {Text::lab2_answer_general,
     "Temperature acts on the systematic part of the output: the bias follows the temperature "
     "and a polynomial in T removes it; left in, it passes for a large drift and spoils the "
     "Allan deviation at long tau. Gyros of the better classes are therefore calibrated against "
     "temperature (the manual: temperature errors can make up 30-40 % of the drift)."},
    {Text::lab2_conclusions, "Conclusions"},
    {Text::lab2_conclusion_widest,
     "{} against {}, the largest difference — {}: {:.3g} times ({} over {})."},
    {Text::lab2_conclusion_temperature,
     "{} is the more temperature-sensitive over its ramp: |c1| = {} against {} deg/h/degC for {}."},
    {Text::an_manual_k,
     "K read the manual's way (docs/manual_notes.md): the +1/2 line read at tau = 1 s gives "
     "K/sqrt(3) = {}, the -2 line's level at 1 Hz K/(2 pi) = {} deg/h/sqrt(s); this table reads "
     "the line at tau = 3 s (eq. 20: K^2 tau/3) and the PSD as K^2/(2 pi f)^2, both equal to K."},
    {Text::an_manual_q,
     "Quantisation: the manual's eq. 20 writes C^2/tau^2 with C = sqrt(3) Q = {} deg/h*s; IEEE "
     "Std 952 and this report write 3 Q^2/tau^2, Q = {} deg/h*s (docs/manual_notes.md)."},
    {Text::lab2_q_eq17, "Allan deviation from the PSD"},
    {Text::lab2_m_eq17, "eq. (17) on the fit's PSD: largest disagreement"},
    {Text::lab2_eq17_cell, "{:+.1f} at {} s ({} of {} taus within 95 %)"},
    // ---- analyze's report ----
    {Text::an_eq17, "Allan deviation from the PSD (eq. 17)"},
    {Text::an_eq17_value,
     "the fitted model's PSD through the manual's eq. (17) lies inside the measured 95 % "
     "intervals at {} of {} taus; largest disagreement {:+.1f} % at tau = {} s ({:.2g} times the "
     "interval's half-width)"},
    {Text::an_eq17_none, "not compared (no fit or no intervals)"},
    {Text::an_legend_eq17, "eq. (17): from the fitted PSD"},
    {Text::an_not_visible, "not visible"},
    {Text::an_no_bound, "no bound"},
    {Text::an_random_bias_wiener, "a Wiener process (rate random walk), K = {} deg/h/sqrt(s)"},
    {Text::an_random_bias_gauss_markov,
     "a first-order Gauss-Markov process, sigma = {} deg/h, Tc = {} s"},
    {Text::an_random_bias_none,
     "not visible in this record (neither a Wiener nor a Gauss-Markov process is supported by "
     "the data)"},
    {Text::an_bandwidth_none,
     "none resolved (the first taus follow N/sqrt(tau): the samples' white noise is not visibly "
     "filtered)"},
    {Text::an_bandwidth_moving_average,
     "a moving average over {} samples (cut-off {} Hz), on {} % of the white noise (lag-1 "
     "correlation of its samples {}); it lowers the Allan variance at the first tau by {} %, and "
     "N is the white level above it"},
    {Text::an_bandwidth_butterworth,
     "a second-order Butterworth low-pass at {} Hz, on {} % of the white noise (lag-1 "
     "correlation of its samples {}); it lowers the Allan variance at the first tau by {} %, and "
     "N is the white level above it"},
    {Text::an_bandwidth_first_order,
     "time constant {} s, first-order cut-off {} Hz, on {} % of the white noise (lag-1 "
     "correlation of its samples {}); it lowers the Allan variance at the first tau by {} %, and "
     "N is the white level above it"},
    {Text::an_bandwidth_beyond_memory,
     "a filter of no modelled kind, known beyond its memory (the first taus, inside it, are left "
     "out): there the white noise's Allan variance is N^2/tau (1 - c tau0/tau) with c = {} "
     "samples (a first-order low-pass with the same c would cut off at {} Hz); it lowers the "
     "Allan variance at the first tau kept by {} %, and N is the white level above it"},
    {Text::an_bandwidth_shape_free,
     "; the 95 % intervals also span the fit that assumes no filter kind: the first {} tau(s), "
     "inside its memory, left out and the rest taken as N^2/tau (1 - c tau0/tau)"},
    {Text::an_bandwidth_shape_free_all,
     "; the 95 % intervals also span the fit that assumes no filter kind: no tau lies inside "
     "its memory, and every tau is taken as N^2/tau (1 - c tau0/tau)"},
    {Text::an_bandwidth_shape_free_n, ", which gives N = {} deg/h/sqrt(Hz)"},
    {Text::an_bandwidth_shape_decides,
     " ({} % from the kind's: the filter's shape at the first taus decides N in this record, "
     "and N's interval spans both)"},
    {Text::an_lines_none, "none found in the PSD"},
    {Text::an_line, "{} Hz ({} Hz wide), {} deg/h rms, {} times the PSD's floor"},
    {Text::an_line_slow,
     "{} Hz (a period of {} s, {} Hz wide), {} deg/h rms, {} times the PSD's floor"},
    {Text::an_lines_scale,
     " (the variance the fit used: {} times the PSD bins', as the Allan deviation's first taus "
     "show it)"},
    {Text::an_line_removed,
     "{} Hz (a period of {} s), a sinusoid of {} deg/h amplitude ({} deg/h rms), {} times the "
     "PSD's floor, taken out of the record before the Allan variance"},
    {Text::an_line_removed_periodic,
     "{} Hz (a period of {} s), a periodic disturbance of {} deg/h rms that is not one sinusoid "
     "(its first harmonic of {} deg/h amplitude and {} more up to {} times its frequency), {} "
     "times the PSD's floor, taken out of the record as a whole before the Allan variance"},
    {Text::an_lines_tail, " (its Allan variance is part of the fit, not of any noise term)"},
    {Text::an_drift_unchecked, "not checked (the record holds under 32 blocks of 256 samples)"},
    {Text::an_drift_steady,
     "no trend over the run at tau {} to {} s ({} blocks in time order, largest Mann-Kendall "
     "|z| {}; a call needs {})"},
    {Text::an_drift_trend,
     "the Allan variance trends over the run at tau {} s (Mann-Kendall |z| {}, the last eighth "
     "of the blocks {} times the first): see the notes and the report's figure over the run"},
    {Text::an_class_both, "both criteria agree"},
    {Text::an_class_by_arw, "decided by the angle random walk (the worse of the two)"},
    {Text::an_class_by_bias_instability, "decided by the bias instability (the worse of the two)"},
    {Text::an_class_sentence,
     "{} ({}; by bias instability {} deg/h: {}; by ARW {} deg/sqrt(h): {})"},
    {Text::an_class_strategic, "strategic"},
    {Text::an_class_navigation, "navigation"},
    {Text::an_class_intermediate, "intermediate"},
    {Text::an_class_tactical, "tactical"},
    {Text::an_class_consumer, "consumer"},
    {Text::an_record_title, "{} ({})"},
    {Text::an_plots_off, "plotting was turned off"},
    {Text::an_gnuplot_missing,
     "gnuplot could not be run ({}); install gnuplot (Debian: gnuplot-nox) to draw them"},
    {Text::an_page_title, "foglab report: {}"},
    {Text::an_recording, "Recording"},
    {Text::an_file, "file"},
    {Text::an_rate_channel, "rate channel"},
    {Text::an_temperature_channel, "temperature channel"},
    {Text::an_none, "none"},
    {Text::an_input_unit, "input unit"},
    {Text::an_analysed_in, "{} (analysed in deg/h)"},
    {Text::an_samples, "samples"},
    {Text::an_sample_rate, "sample rate"},
    {Text::an_duration, "duration"},
    {Text::an_duration_value, "{:.1f} s ({:.3g} h)"},
    {Text::an_systematic, "Systematic part (bias and its temperature dependence)"},
    {Text::an_systematic_fit,
     "Least-squares polynomial of degree {} in (T - t_ref), t_ref = {:.4g} degC{}{}. Standard "
     "errors from the fitted noise model."},
    {Text::an_degree_chosen, ", degree chosen by the criterion"},
    {Text::an_constant_fallback_why, ", constant fallback (the temperature barely moves)"},
    {Text::an_constant_fallback, ", constant fallback"},
    {Text::an_coefficient, "coefficient"},
    {Text::an_standard_error, "standard error"},
    {Text::an_systematic_bias, "systematic bias at t_ref"},
    {Text::an_lab_constant, "lab's polyfit(T, Y, 2) constant term"},
    {Text::an_not_meaningful, " (not meaningful: the span is too small)"},
    {Text::an_temperature_span, "temperature span"},
    {Text::an_span_value, "{:.4g} degC ({:.4g} to {:.4g} degC)"},
    {Text::an_residual_rms, "residual rms"},
    {Text::an_no_temperature_mean,
     "No temperature: only the record mean (the constant bias), {:.6g} deg/h, was removed."},
    {Text::an_no_temperature,
     "No temperature: only the record mean (the constant bias) was removed."},
    {Text::an_noise_model, "Noise model (IEEE Std 952, fitted to the Allan variance)"},
    {Text::an_terms_chosen,
     "Terms chosen: {}; {} tau points, dispersion {:.3g}. Intervals are 95 %; a term the record "
     "cannot resolve gets a one-sided 95 % upper bound."},
    {Text::an_fit, "Fit: {}."},
    {Text::an_parameter, "parameter"},
    {Text::an_meaning, "meaning"},
    {Text::an_status, "status"},
    {Text::an_status_resolved, "resolved"},
    {Text::an_status_upper_bound, "upper_bound"},
    {Text::an_status_absent, "absent"},
    {Text::an_sym_n, "N"},
    {Text::an_sym_b, "B"},
    {Text::an_sym_k, "K"},
    {Text::an_sym_r, "R"},
    {Text::an_sym_q, "Q"},
    {Text::an_sym_gm, "GM"},
    {Text::an_param_gm_sigma, "gm_sigma"},
    {Text::an_param_gm_tc, "gm_tc"},
    {Text::an_meaning_n, "white rate noise (angle random walk = N/60 deg/sqrt(h))"},
    {Text::an_meaning_n_accel,
     "white acceleration noise (velocity random walk = 60 N m/s/sqrt(h))"},
    {Text::an_meaning_b, "flicker, bias instability coefficient (plateau 0.664 B)"},
    {Text::an_meaning_k, "rate random walk (Wiener process intensity)"},
    {Text::an_meaning_r, "rate ramp"},
    {Text::an_meaning_q, "angle quantisation"},
    {Text::an_meaning_gm_sigma, "Gauss-Markov random bias, standard deviation"},
    {Text::an_meaning_gm_tc, "Gauss-Markov random bias, correlation time"},
    {Text::an_arw, "angle random walk (N/60)"},
    {Text::an_vrw, "velocity random walk (60 N)"},
    {Text::an_bandwidth, "sensor bandwidth"},
    {Text::an_lines, "spectral lines"},
    {Text::an_drift, "short-tau stationarity"},
    {Text::an_steps, "bias steps"},
    {Text::an_steps_levelled, ", levelled before the analysis (the notes list them)"},
    {Text::an_steps_as_noise,
     ", left in: the bias jumps as a process, not at a few glitches (the notes say why)"},
    {Text::an_left_in, ", left in"},
    {Text::an_spikes, "spikes"},
    {Text::an_spikes_value, "{} (beyond {} deg/h from their neighbours' mean){}"},
    {Text::an_heavy_tail,
     "; heavy-tailed noise (its tail a power {} of the size): its outliers are kept, a "
     "spike departs by more than {} deg/h"},
    {Text::an_spikes_replaced, ", replaced by that mean"},
    {Text::an_quantisation, "output quantisation"},
    {Text::an_quantisation_value,
     "steps of {} deg/h (LSB); rounding noise {} deg/h/sqrt(Hz), inside N"},
    {Text::an_quantisation_none, "none seen in the samples"},
    {Text::an_bias_instability, "bias instability (ADEV minimum)"},
    {Text::an_bias_instability_value, "{} deg/h at tau = {} s{}"},
    {Text::an_at_edge_why, " (at the end of the tau range: the true minimum may lie beyond it)"},
    {Text::an_readings, "The lab's graphical readings beside the fit"},
    {Text::an_quantity, "quantity"},
    {Text::an_adev_reading, "ADEV reading"},
    {Text::an_psd_reading, "PSD reading"},
    {Text::an_fit_interval, "fit (95 % interval)"},
    {Text::an_reading_n, "white noise N (ADEV at tau = 1 s on the -1/2 line; PSD flat level)"},
    {Text::an_reading_k,
     "Wiener intensity K (ADEV at tau = 3 s on the +1/2 line; PSD -2 slope at 1 Hz)"},
    {Text::an_reading_bias_instability, "bias instability (ADEV minimum; fit: flicker B)"},
    {Text::an_value_at, "{} at {} s"},
    {Text::an_random_bias, "Random bias"},
    {Text::an_random_bias_is, "The random part of the bias is {}."},
    {Text::an_hypothesis, "hypothesis"},
    {Text::an_deviance, "deviance"},
    {Text::an_criterion, "criterion"},
    {Text::an_no_random_bias, "no random bias"},
    {Text::an_wiener_process, "Wiener process"},
    {Text::an_gauss_markov_process, "Gauss-Markov process"},
    {Text::an_slopes,
     "Log-log slope of the ADEV over its last three points: {} (+0.5 for a Wiener process, "
     "negative after a Gauss-Markov hump); of the PSD over its lowest decade: {} (-2 for a "
     "Wiener process, about 0 on a Gauss-Markov plateau)."},
    {Text::an_class, "Accuracy class (lab manual, Table 1)"},
    {Text::an_class_accel, "Accuracy class"},
    {Text::an_no_accelerometer_class,
     "none: the lab manual's Table 1 classes gyroscopes only (by bias instability and angle "
     "random walk); it does not apply to an accelerometer"},
    {Text::an_notes, "Notes"},
    {Text::an_md_recording,
     "Recording `{}`, channel {}, temperature {}: {} samples at {} Hz ({:.3g} h){}."},
    {Text::an_md_gaps, ", {} gap(s) with {} samples missing (analysed by contiguous stretches)"},
    {Text::an_md_systematic, "Systematic part"},
    {Text::an_md_polynomial, "Polynomial of degree {} in (T - {:.4g} degC){}{}."},
    {Text::an_md_systematic_bias,
     "systematic bias at {:.4g} degC: **{:.6g} deg/h**; temperature span {:.4g} degC"},
    {Text::an_md_no_temperature_mean,
     "No temperature: only the record mean, {:.6g} deg/h, was removed."},
    {Text::an_md_no_temperature, "No temperature: only the record mean was removed."},
    {Text::an_md_noise, "Noise model (terms {}, 95 % intervals)"},
    {Text::an_md_at_edge, " (at the end of the tau range)"},
    {Text::an_md_arw, "ARW {} deg/sqrt(h); bias instability (ADEV minimum) **{} deg/h** at {} s{}"},
    {Text::an_md_vrw,
     "VRW {} m/s/sqrt(h); bias instability (ADEV minimum) **{} m/s^2** ({} mg) at {} s{}"},
    {Text::an_md_readings, "graphical readings: ADEV N {}, K {}, minimum {} deg/h; PSD N {}, K {}"},
    {Text::an_md_random_bias, "random bias"},
    {Text::an_md_class, "accuracy class"},
    {Text::an_plot_gap, "gap ({} found, nothing interpolated)"},
    {Text::an_plot_step, "bias step ({} found, levelled)"},
    {Text::an_plot_step_as_noise, "bias jump ({} found, left in as the bias's process)"},
    {Text::an_plot_gap_jump, "bias jump across a gap ({} found, measured, not levelled)"},
    {Text::an_plot_spike, "spike ({} found, replaced)"},
    {Text::an_plot_time, "{}: rate and temperature"},
    {Text::an_axis_time, "time [h]"},
    {Text::an_axis_rate, "rate [deg/h]"},
    {Text::an_axis_temperature, "temperature [degC]"},
    {Text::an_legend_envelope, "rate, min-max of {} samples"},
    {Text::an_legend_block_mean, "rate, block mean"},
    {Text::an_legend_rate, "rate"},
    {Text::an_legend_temperature, "temperature (right axis)"},
    {Text::an_legend_temperature_channel, "temperature {} (right axis)"},
    {Text::an_plot_bias, "{}: bias against temperature"},
    {Text::an_axis_bias, "bias (block mean of the rate) [deg/h]"},
    {Text::an_legend_block_means_s, "block means ({:.3g} s)"},
    {Text::an_legend_block_means, "block means"},
    {Text::an_legend_polynomial, "fit: degree {} in (T - {:.4g} degC){}"},
    {Text::an_source_psd, "PSD reading"},
    {Text::an_source_fit, "fit"},
    {Text::an_plot_psd, "{}: square root of the PSD of the residual (two-sided)"},
    {Text::an_axis_frequency, "frequency [Hz]"},
    {Text::an_axis_sqrt_psd, "sqrt(PSD) [deg/h/sqrt(Hz)]"},
    {Text::an_legend_welch_smoothed, "Welch estimate, log-smoothed"},
    {Text::an_legend_welch, "Welch estimate"},
    {Text::an_legend_line_band, "spectral line {} Hz, {} deg/h rms (in the fit as known noise)"},
    {Text::an_legend_line_removed_band,
     "spectral line {} Hz, {} deg/h rms (a sinusoid taken out of the record)"},
    {Text::an_legend_periodic_band,
     "periodic disturbance {} Hz and its harmonics, {} deg/h rms (taken out of the record)"},
    {Text::an_legend_white_level, "white noise level N = {} deg/h/sqrt(Hz) ({})"},
    {Text::an_legend_random_walk, "random walk K/(2 pi f), K = {} deg/h/sqrt(s) ({})"},
    {Text::an_plot_adev, "{}: overlapping Allan deviation of the residual"},
    {Text::an_axis_tau, "tau [s]"},
    {Text::an_axis_adev, "Allan deviation [deg/h]"},
    {Text::an_legend_bandwidth, "sensor bandwidth (white level lowered > 1 %)"},
    {Text::an_legend_first_taus,
     "first {} tau(s) left out of the fit (no modelled filter follows)"},
    {Text::an_legend_oadev, "OADEV"},
    {Text::an_legend_term_q, "quantisation Q (-1)"},
    {Text::an_legend_term_n, "white noise N (-1/2)"},
    {Text::an_legend_term_b, "flicker B (0)"},
    {Text::an_legend_term_k, "random walk K (+1/2)"},
    {Text::an_legend_term_r, "rate ramp R (+1)"},
    {Text::an_legend_term_gm, "Gauss-Markov sigma, Tc"},
    {Text::an_legend_white_bandwidth, "white noise N with the sensor bandwidth (f_c {} Hz)"},
    {Text::an_legend_line, "spectral line {} Hz"},
    {Text::an_legend_lines, "{} spectral lines"},
    {Text::an_legend_fit, "fit {}"},
    {Text::an_legend_minimum, "minimum {} deg/h at {} s"},
    {Text::an_legend_drift, "trends over the run (Mann-Kendall, {} blocks)"},
    {Text::an_plot_drift, "{}: short-tau Allan deviation over the run"},
    {Text::an_axis_drift_change, "block's Allan deviation, change from the blocks' mean [%]"},
    {Text::an_legend_drift_tau, "tau {} s: z {}, last eighth / first {}"},
    {Text::an_legend_drift_steady, "no trend: tau {} s"},
    {Text::an_caption_time,
     "Rate (block means, with the minimum and maximum of each block) and temperature against "
     "time."},
    {Text::an_caption_bias,
     "Bias (block means of the rate) against temperature, with the fitted polynomial."},
    {Text::an_caption_psd,
     "Square root of the two-sided PSD of the residual, log-log with equal decades, with the "
     "white-noise level and the random-walk line of the graphical readings."},
    {Text::an_caption_adev,
     "Overlapping Allan deviation of the residual with its 95 % confidence band, the fitted "
     "model and the line of each term, log-log with equal decades."},
    {Text::an_caption_drift,
     "The record cut into {} blocks in time order: the overlapping Allan deviation inside each "
     "block at the short taus, as a change from the blocks' mean, against the block's middle. "
     "In colour the taus whose values trend (Mann-Kendall test, p < 1e-4 at each tau), the "
     "ratio of the last eighth's Allan variance to the first eighth's beside them; in grey "
     "the taus checked that do not trend, which show the scatter of a stationary block."},
    // ---- the analyses' notes ----
    {Text::note_gaps,
     "{} gap(s) in the time axis, {} samples ({:.6g} s, {:.3g} % of the span) missing; "
     "the record was analysed as its {} contiguous stretches (longest {:.6g} s): the "
     "Allan deviation pools the terms inside each stretch (and, where a note says so, "
     "those whose clusters miss a few samples) and the PSD the Welch segments inside "
     "each stretch (segments spanning a gap are left out); nothing was interpolated"},
    {Text::note_gap_clusters,
     "{} of the Allan deviation's taus ({:.6g} to {:.6g} s) also take the terms that span a "
     "gap where each of their two clusters misses at most {:.3g} % of its samples, each "
     "cluster's mean over the samples it has (nothing interpolated; their edf is the gap-free "
     "record's for the share of its terms used): short gaps no longer end the taus at the "
     "longest stretch"},
    {Text::note_allan_terms_spread,
     "at tau {} s the Allan terms spread {} times more than the identified noise type "
     "allows (measured from the means of batches of terms and their neighbours' differences, "
     "beyond chance at 99.9 %: a resonance or dither keeps the terms correlated); the edf "
     "there is divided by that much, which widens the 95 % intervals and lightens those "
     "points in the noise fit"},
    {Text::note_step_item, "{:+.4g} deg/h at {:.6g} s"},
    {Text::note_steps,
     "{} bias step(s): {} (each beyond {:g} robust spreads of the difference of the "
     "window means on either side); {}"},
    {Text::note_steps_levelled,
     "the record was levelled (each size subtracted from the samples after it) before "
     "the analysis"},
    {Text::note_steps_kept, "they were left in (not levelled)"},
    {Text::note_steps_as_noise,
     "{}: the bias jumps as a process (a random telegraph or popcorn noise), not at a few "
     "glitches, so none was levelled and the statistics take the jumps as noise (a "
     "Gauss-Markov term follows such a process's Allan deviation)"},
    {Text::note_steps_beyond_limit, "more jumps follow beyond these {}, the search's limit"},
    {Text::note_steps_wander,
     "levelling them would make the record wander more than chance allows (the means of "
     "its neighbouring sixteenths)"},
    {Text::note_steps_two_levels, "they go back and forth between two levels"},
    {Text::note_steps_at_temperature_turns,
     "the {} bias jumps lie at turns of the temperature (where its rate of change changes "
     "sign; {} turns), each against that change the same way: the bias follows the "
     "temperature's rate of change dT/dt (in a FOG, the Shupe effect of a temperature gradient "
     "along the coil), not a random process, and in a cycle of ramps it jumps with dT/dt, as "
     "they did. The temperature law is a polynomial in T: a dT/dt that changes smoothly (a "
     "sinusoidal cycle) is not taken out, and the noise terms would carry it"},
    {Text::note_gap_jump_item,
     "{:+.4g} deg/h where the record resumes at {:.6g} s ({:.3g} spreads)"},
    {Text::note_gap_jumps,
     "{} bias jump(s) across gaps: {} (each beyond {:g} robust spreads of the same difference "
     "of window means taken as far apart where nothing is missing, which holds the drift and "
     "the noise's own wandering over that time); the stretches are analysed apart, so a jump "
     "does not enter the statistics, and it is not levelled"},
    {Text::note_spikes,
     "{} spike(s): isolated samples departing from the mean of their neighbours by "
     "more than {:.4g} deg/h ({:.3g} robust standard deviations); {}"},
    {Text::note_spikes_replaced,
     "each was replaced by the mean of its neighbours before the analysis"},
    {Text::note_spikes_kept, "they were left in (not removed)"},
    {Text::note_heavy_tail,
     "the noise is heavy-tailed: {} samples depart from their neighbours' mean by 5 to 8 "
     "robust standard deviations, where Gaussian noise would put {:.2g} (its tail falls "
     "as a power {:.2g} of the size); these outliers are the noise's own and stay in the "
     "record (the angle accumulates their variance too), and only a departure beyond "
     "{:.4g} deg/h, which that tail reaches with probability 0.05 in the whole record, "
     "is taken for a spike; N's 95 % interval is widened for the scatter such a noise "
     "gives its sample variance (excess kurtosis {:.3g}), the other terms' intervals "
     "assume Gaussian noise"},
    {Text::note_allan_drift,
     "the Allan variance at tau {} s changes over the record: cut into {} blocks in time "
     "order, its values trend (Mann-Kendall |z| {}, beyond {:.3g}: p < 1e-4 at each "
     "tau), the last eighth's {} times the first "
     "eighth's; the sensor's short-term noise is not stationary (a warm-up, a resonance "
     "or a filter moving with the temperature), the whole record's Allan deviation there "
     "is an average over it, and its 95 % intervals, which assume a stationary record, "
     "understate how far it may lie from any one state of the sensor"},
    {Text::range_of, "{:.3g} to {:.3g}"},
    {Text::one_of, "{:.3g}"},
    {Text::note_no_temperature,
     "no temperature: the systematic part is the mean rate only (removed by the "
     "statistics)"},
    {Text::note_quantised,
     "the output is quantised in steps of {:.6g} deg/h ({} distinct values in the "
     "first {} samples); rounding adds white noise of level {:.4g} deg/h/sqrt(Hz), "
     "{:.3g} % of N^2, {}"},
    {Text::note_quantised_without_white,
     "the output is quantised in steps of {:.6g} deg/h ({} distinct values in the "
     "first {} samples); rounding adds white noise of level {:.4g} deg/h/sqrt(Hz) (the "
     "fit resolved no white noise to compare it with), {}"},
    {Text::note_temperature_quantised,
     "the temperature is read in steps of {:.4g} degC ({} readings, changing on {} "
     "samples, every {:.3g} s on average): the temperature law is fitted against the "
     "temperature between the steps (linear between the instants where the reading "
     "changes, at the boundary of the two readings), not against the staircase, "
     "whose error times the law's slope would stay in the residual"},
    {Text::note_temperature_kelvin,
     "the temperature reads {:.5g} to {:.5g} degC, above 200 degC throughout, where no gyro "
     "is tested: the channel is likely in kelvin, and foglab reads degC. The law's "
     "coefficients about the mean temperature (c1, c2, c3, and the bias at T_ref) do not "
     "depend on it, but T_ref, the temperatures shown and the lab's constant term (the "
     "bias extrapolated to 0 degC) are those of a reading 273.15 too high: convert the "
     "channel (subtract 273.15) for those"},
    {Text::note_quantised_known, "which the fit takes as known: N is the sensor's own white level"},
    {Text::note_quantised_distorting,
     "which the fitted N includes: the step is more than twice the samples' "
     "sample-to-sample spread, so the rounding is not noise-like and the short-tau "
     "statistics are distorted (N, B and the class then describe the output word, not "
     "the sensor; spikes must depart by four steps, and steps be at least one)"},
    {Text::note_minimum_at_edge,
     "the Allan deviation is lowest at the {} of its tau range ({:.4g} s): the bias "
     "instability may be lower than reported"},
    {Text::note_minimum_inside_filter,
     "the Allan deviation is lower inside the output filter's memory ({:.4g} deg/h at "
     "{:.4g} s; the memory ends near {:.3g} s), where the filter, not the gyro's noise, "
     "lowers it: the bias instability is read beyond it, {:.4g} deg/h at {:.4g} s"},
    {Text::word_start, "start"},
    {Text::word_end, "end"},
    {Text::note_fit_degenerate,
     "noise-model fit: {}; there is no ARW, and the class verdict takes the worst ARW "
     "class"},
    {Text::note_no_white,
     "no white rate noise resolved: the ARW for the class verdict is its upper bound"},
    {Text::note_fit, "noise-model fit: {}"},
    {Text::fit_others_converged, "every candidate converged"},
    {Text::fit_others_limited, "{} of {} candidates stopped at the iteration limit"},
    {Text::fit_converged,
     "converged: the chosen model {} in {} iteration(s) (relative change below {:g}); "
     "{}"},
    {Text::fit_iteration_limit,
     "iteration limit: the chosen model {} stopped after {} iterations without its "
     "fitted Allan variances settling to a relative change of {:g}; {}; its estimates "
     "are those of the last iteration"},
    {Text::fit_degenerate,
     "degenerate: no candidate model could be fitted to the {} Allan-variance points "
     "(no subset of terms has positive coefficients)"},
    {Text::fit_first_taus_left_out,
     "the first {} tau(s) ({:.6g} s to {:.6g} s) were left out: no modelled output "
     "filter (first-order, moving average, Butterworth) followed them (the fit's "
     "dispersion was above 4 with them, and leaving them out lowered it by more than "
     "30 %), so the terms rest on the taus from {:.6g} s, beyond the filter's memory, with "
     "its effect there taken as 1 - c tau0/tau on the white noise; the intervals span the "
     "c they do not tell apart"},
    {Text::fit_ramp_set_aside,
     "the model {} had a rate ramp R = {:.4g} deg/h/s [{:.4g}, {:.4g}], but the "
     "record's least-squares slope over its {:.6g} s is {:.4g} deg/h/s, and the "
     "model's other terms ({}) allow {:.4g} deg/h/s at most (3 standard deviations of "
     "the slope beyond it): the rise at the last taus is not a ramp in this record, so "
     "the models with R are left out"},
    {Text::fit_gm_set_aside,
     "the Gauss-Markov model {} fitted better (criterion {:.1f} against {:.1f}, less "
     "than two parameters' worth), but its Tc of {:.4g} s has the 95 % interval "
     "[{:.4g}, {:.4g}] s, which does not close below the longest tau / {} = {:.4g} s: "
     "the record does not show the process turning away from a random walk, so the "
     "Wiener model {} is taken"},
    {Text::temp_too_flat,
     "the temperature moves by only {:.3g} degC (block means; below {:.3g} degC), too "
     "little to see a temperature dependence: the systematic part is a constant, the "
     "mean rate{}"},
    {Text::temp_degree_asked, " (degree {} was asked for)"},
    {Text::temp_as_asked, "polynomial of degree {} in temperature, as asked"},
    {Text::temp_chosen,
     "degree {} chosen by the criterion W_d + {:.3g} d (Wald statistic of the higher "
     "coefficients with the noise model's covariance) = {} for d = 0..{}{}"},
    {Text::temp_chosen_from,
     ", from degree {} up (the temperature moves by {:.3g} degC, so its linear "
     "coefficient is measured and reported with its standard error, significant or "
     "not)"},
    {Text::ev_criteria,
     "criterion (-2 ln L + penalty x parameters): no random bias {}, Wiener "
     "{}, Gauss-Markov {}"},
    {Text::ev_wiener,
     "Wiener random bias: the Allan deviation rises at the long taus (end slope "
     "{:.2f}, +0.5 expected) and {}; {}"},
    {Text::ev_rw_best, "a random walk explains it best"},
    {Text::ev_rw_explains, "a random walk explains it ({})"},
    {Text::ev_gauss_markov,
     "first-order Gauss-Markov random bias (Tc = {:.3g} s): the Allan deviation rises "
     "and turns down again (end slope {:.2f}), the PSD flattens at low frequency "
     "(slope {:.2f}); {}"},
    {Text::ev_none,
     "no random bias visible in this record: neither a random walk nor a Gauss-Markov "
     "term improves the fit enough (end slope {:.2f}); {}"},
    {Text::cal_note_stretches_left_out,
     "{} level stretches of the output left out: shorter than two 1 s blocks, or than "
     "the settle time ({} s) plus {} samples"},
    {Text::cal_note_plateaus_from_output,
     "plateaus found from the output: {} where it stays level (1 s means stepping less "
     "than {:.3g} LSB), each plateau's rate the rate column's mean over it"},
    {Text::cal_note_plateau_left_out,
     "the plateau at {} deg/s from sample {} ({} samples) is left out: shorter than "
     "the settle time ({} s) plus {} samples"},
    {Text::cal_note_more_left_out,
     "{} more plateaus left out, {} in all: is the rate column the commanded rate? (a "
     "measured rate: find the plateaus from the output)"},
    {Text::cal_note_alike_no_fit,
     "the plateaus are weighted alike: no noise model could be fitted to the residual "
     "record ({})"},
    {Text::cal_note_alike_not_pd,
     "the plateaus are weighted alike: the noise model's covariance of the plateau "
     "means is not positive definite"},
    {Text::cal_note_no_asymmetry, "no asymmetry fitted: the run has rates of one sign only"},
    {Text::cal_note_degree_limited,
     "nonlinearity fitted to degree {} only: the run has {} distinct rates"},
    {Text::table_note_no_edf,
     "the table has no counts, edf or bounds: the fit assumed OADEV of a record 10 "
     "times the longest tau (white-FM edf), so its parameters have no intervals and no "
     "upper bounds, and which terms it resolved rests on that assumption"},
    {Text::table_note_some_no_edf,
     "{} of {} taus have no edf, bounds or count and were left out of the fit"},
    {Text::table_note_edf_from_counts,
     "edf from the counts, taken as OADEV terms with SP 1065's white-FM formula (the "
     "table does not say its noise types)"},
    {Text::io_note_mat_integer, "{}: variable '{}' is {}: its integers are converted to double{}"},
    {Text::io_note_mat_integer_wide, " (those beyond 2^53 in magnitude are rounded)"},
    {Text::io_note_zero_stamps,
     "every header.stamp of topic '{}' is zero: the times are the bag's receive times, "
     "which carry the recording host's delays"},
    {Text::io_note_duplicates,
     "{} of the {} messages of topic '{}' dropped: each fell on the time slot of the "
     "message before it, or earlier (a repeated or out-of-order {})"},
    {Text::io_stamp_header, "header.stamp"},
    {Text::io_stamp_receive, "bag receive time"},
    {Text::io_note_time_jitter,
     "{}: the times in '{}' are not evenly spaced ({} of the {} steps differ from the median "
     "step, {} s, by more than 1 %): they are read as a uniform sampling grid with jitter (rms "
     "{} s, largest {} s), as a ROS bag's stamps are: each sample is put on the grid's nearest "
     "slot, a slot skipped is a gap, nothing is interpolated, and the sample rate, {} Hz, is "
     "the least-squares slope of time against slot"},
    {Text::io_note_time_bursts,
     "{}: the times in '{}' show {} gaps among {} samples, with {} samples missing on a grid of "
     "{} s steps: more are missing than present. If the times are a logger's, stamping the "
     "samples in bursts as they arrive, they say nothing of the sampling: give the sample "
     "rate in ReadOptions::sample_rate_hz to read the samples as evenly spaced"},
    {Text::io_note_time_rows_dropped,
     "{} of the {} rows dropped: each fell on the time slot of the row before it, or earlier "
     "(a repeated time in '{}')"},
};

}  // namespace

std::span<const CatalogueEntry> catalogue_en() { return kEntries; }

}  // namespace foglab::detail
