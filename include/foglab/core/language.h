// foglab — the languages foglab writes: every heading, label, unit and sentence a report
// prints, and every note the analyses leave (model::AnalysisResult::notes and the like), lives
// in one catalogue per language (src/core/catalogue_en.cc, catalogue_ru.cc), keyed by Text; the
// code only says which key, with the numbers for its fmt placeholders. The Russian catalogue
// uses the lab manual's own terms (смещение нуля, масштабный коэффициент, ...) and units (°/ч,
// °/с, °C; е.м.р. for the output's least significant bit, млн⁻¹ for ppm).
//
// A note is a Message: its key and its values, written in a language when it is shown (the
// JSON carries the English).
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "foglab/core/noise_model.h"

namespace foglab {

enum class Language { en, ru };

/// "en", "ru".
std::string_view to_string(Language language);
/// Parses "en" or "ru" (any case); throws UsageError naming the choices otherwise.
Language language_from_string(std::string_view text);
/// The HTML lang attribute's value: "en", "ru".
std::string_view html_lang(Language language);

/// The catalogues' keys.
enum class Text {
  // shared by the reports
  verbatim,       ///< "{}": a sentence from outside foglab, as it is
  plots_skipped,  ///< "The plots were skipped: {reason}."
  plot_skipped,   ///< "This plot was skipped: {reason}"
  note,           ///< "Note: {text}"
  footer,         ///< the page footer: {version}
  value,          ///< table heading
  interval95,     ///< table heading
  unit,           ///< table heading
  // calibrate's report
  cal_title,              ///< "foglab calibrate: {run}"
  cal_triad_title,        ///< "foglab calibrate, a triad: {runs}"
  cal_section,            ///< "Calibration"
  cal_run,                ///< {plateaus} {temperatures} {full scale} {T_ref}: the run and eq. (10)
  cal_coefficient,        ///< table heading
  cal_row_s,              ///< S
  cal_row_sk,             ///< s_{k}
  cal_row_ak,             ///< a_{k}
  cal_row_a,              ///< A
  cal_row_u0,             ///< u0
  cal_row_u0_rate,        ///< u0 as a rate
  cal_row_bk,             ///< b_{k}
  unit_lsb_per_deg_s,     ///< LSB/(deg/s)
  unit_ppm_per_degc_k,    ///< ppm/degC^{k}
  unit_ppm_fs,            ///< ppm of full scale
  unit_ppm,               ///< ppm
  unit_percent,           ///< %
  unit_lsb,               ///< LSB
  unit_deg_h,             ///< deg/h
  unit_lsb_per_degc_k,    ///< LSB/degC^{k}
  unit_deg_h_per_degc,    ///< "deg/h/degC": the units shared by the reports
  unit_deg_h_per_degc_k,  ///< {k}
  unit_s,                 ///< "s"
  unit_hz,                ///< "Hz"
  unit_deg_sqrt_h,        ///< "deg/sqrt(h)"
  unit_deg_h_sqrt_hz,     ///< "deg/h/sqrt(Hz)"
  unit_deg_h_sqrt_s,      ///< "deg/h/sqrt(s)"
  unit_deg_h_s,           ///< "deg/h/s"
  unit_deg_h_times_s,     ///< "deg/h*s"
  unit_m_s_sqrt_h,        ///< "m/s/sqrt(h)"
  unit_deg_s,             ///< "deg/s"
  unit_rad_s,             ///< "rad/s"
  unit_m_s2,              ///< "m/s^2"
  unit_mg,                ///< "mg"
  cal_nonlinearity,       ///< {ieee} {lab1} {degree}
  cal_noise,              ///< {N} {ARW} {rms} {dof}
  cal_weighting_noise,    ///< {N} {B} {K} {gm sigma} {gm Tc} {chi2}
  cal_weighting_alike,
  cal_budget,  ///< "Error budget at full scale (eq. 13, 95 %):"
  cal_budget_bias,
  cal_budget_scale_factor,
  cal_budget_nonlinearity,
  cal_budget_noise,
  cal_corrected_rate,  ///< "Corrected rate (eq. 11):"
  cal_equation,        ///< eq. (11): {bias} {bias terms} {S} {S terms} {f terms} {T_ref}
  symbol_rate,         ///< the rate in the equation: "w"
  symbol_dt,           ///< T - T_ref in the equation: "dT"
  cal_plateaus,        ///< the plateaus' table's summary
  cal_col_rate,
  cal_col_samples,
  cal_col_mean,
  cal_col_sd,
  cal_col_temperature,
  cal_col_residual,
  cal_fig_output,  ///< figure captions
  cal_fig_scale_factor,
  cal_fig_residual_rate,
  cal_fig_residual_temperature,
  cal_plot_output,  ///< plot titles
  cal_plot_scale_factor,
  cal_plot_residual_rate,
  cal_plot_residual_temperature,
  cal_axis_rate,  ///< axis labels
  cal_axis_output,
  cal_axis_scale_factor,
  cal_axis_residual,
  cal_axis_temperature,
  cal_legend_temperature,  ///< "{t} degC"
  cal_legend_plateaus,
  cal_misalignment,       ///< heading
  cal_misalignment_text,  ///< what m_ij is
  cal_gyro,               ///< table heading
  cal_own_axis,           ///< the diagonal: "1 (scale factor)"
  cal_gyro_section,       ///< "Gyro {axis} ('{file}')"
  cal_gyro_plot,          ///< "gyro {axis}: {plot title}"
  cal_gyro_figure,        ///< "Gyro {axis}: {caption}"
  // ---- lab 1's report ----
  lab1_title,            ///< "foglab lab 1: variant {variant}": the CLI's page title
  lab1_modulation_none,  ///< the modulations' names (legends)
  lab1_modulation_square,
  lab1_modulation_sine,
  lab1_plot_intensity,  ///< plot titles
  lab1_plot_output,
  lab1_plot_trace_square,
  lab1_plot_trace_sine,
  lab1_plot_ramp_time,
  lab1_plot_sweep,
  lab1_plot_closed_ramp,
  lab1_plot_closed_trace,  ///< {rate deg/s} {rate / Omega_pi/2}
  lab1_plot_closed_ramp_time,
  lab1_plot_off_frequency,  ///< {f / f_m}
  lab1_axis_total_phase,    ///< axis labels
  lab1_axis_detector,
  lab1_axis_input_rate,
  lab1_axis_output_mean,
  lab1_axis_time_us,
  lab1_axis_modulation_phase,
  lab1_axis_time_ms,
  lab1_axis_output_lowpassed,
  lab1_axis_open_scale_factor,
  lab1_axis_closed_scale_factor,
  lab1_axis_closed_output,
  lab1_axis_open_output,
  lab1_axis_feedback_phase,
  lab1_axis_feedback_step,
  lab1_legend_cosine,           ///< the curve gamma (1 + cos phi)
  lab1_legend_time_simulation,  ///< "{modulation}, time simulation"
  lab1_legend_steady_state,     ///< legend entries
  lab1_legend_detector,
  lab1_legend_modulation_phase,
  lab1_legend_input_rate,
  lab1_legend_square_analytic,
  lab1_legend_square_time,
  lab1_legend_sine_time,
  lab1_legend_closed_right,
  lab1_legend_ideal,
  lab1_legend_closed,
  lab1_legend_open_square_right,
  lab1_legend_range_edge,  ///< "+Omega_pi/2"
  lab1_legend_feedback_phase,
  lab1_legend_closed_output,
  lab1_legend_rate,
  lab1_legend_feedback_step,
  lab1_fig_intensity,  ///< figure captions
  lab1_fig_output,
  lab1_fig_trace_square,
  lab1_fig_trace_sine,
  lab1_fig_ramp_time,
  lab1_fig_sweep,
  lab1_fig_closed_ramp,
  lab1_fig_closed_ramp_time,
  lab1_fig_closed_trace_inside,
  lab1_fig_closed_trace_beyond,
  lab1_fig_off_frequency,
  title_university,  ///< the labs' title block
  title_lab,         ///< {number} {title}
  title_lab1_name,
  title_lab2_name,
  title_variant,  ///< {variant}
  title_student,  ///< {name}
  title_group,    ///< {group}
  title_date,     ///< {date}
  title_aim_heading,
  title_aim_lab1,
  title_aim_lab2,
  lab1_coil,  ///< headings
  lab1_open_loop,
  lab1_square_sweep,
  lab1_sine_sweep,
  lab1_closed_loop,
  lab1_checks,
  lab1_conclusions,
  lab1_quantity,  ///< the coil's table
  lab1_row_length,
  lab1_row_radius,
  lab1_row_wavelength,
  lab1_row_group_index,
  lab1_row_scale_factor,
  lab1_row_range,
  lab1_row_range_deg,
  lab1_row_transit_time,
  lab1_row_modulation_frequency,
  lab1_unit_m,             ///< units: m
  lab1_unit_nm,            ///< nm
  lab1_unit_scale_factor,  ///< s (rad per rad/s)
  lab1_unit_us,            ///< us
  lab1_unit_khz,           ///< kHz
  lab1_col_rate,           ///< the sweeps' tables' headings
  lab1_col_output_deg_s,
  lab1_col_scale_factor_1,
  lab1_col_feedback_phase_rad,
  lab1_col_scale_factor_s,
  lab1_col_s_time,
  lab1_col_s_analytic,
  lab1_col_sf_time,
  lab1_col_sf_analytic,
  lab1_col_s,
  lab1_col_sf,
  lab1_square_nonlinearity,  ///< {time %} {analytic %}
  lab1_range_30,             ///< {deg/s} {fraction of Omega_pi/2} {analytic deg/s}
  lab1_sine_nonlinearity,    ///< {%}
  lab1_closed_nonlinearity,  ///< {ppm} {%}
  /// The manual's closed-loop output beside foglab's: {mean phase SF s} {-K_s s} {phase ppm}
  /// {rate ppm}; _shown when the table is in the phase form
  lab1_phase_convention,
  lab1_phase_convention_shown,
  lab1_check_square,         ///< {% of full scale}
  lab1_check_sine,           ///< {% of full scale} {J1(1.8)}
  lab1_check_closed,         ///< {ppm} {ramp end deg/s} {its Omega_pi/2} {lag} {theory}
  lab1_check_off_frequency,  ///< {f / f_m} {spikes %} {theory %} {ratio} {theory ratio}
  lab1_conclusion_none,
  lab1_conclusion_square,  ///< {f_m kHz}
  lab1_conclusion_sine,    ///< {J1(1.8)}
  lab1_conclusion_open,    ///< {%} {30 % range deg/s}
  lab1_conclusion_closed,  ///< {ppm}
  // ---- lab 2's report ----
  lab2_constant_temperature,  ///< a run's condition
  lab2_temperature_ramp,
  lab2_run_title,         ///< {gyro} {condition} {file} {channel}
  lab2_title,             ///< the page's title: {variant}
  lab2_title_files,       ///< the page's title for the lab's own files
  lab2_intro_generated,   ///< {variant} {seed} {files} {answer key}
  lab2_intro_answer_key,  ///< follows lab2_intro_generated
  lab2_intro_files,       ///< {files}
  lab2_intro_method,      ///< follows the intro
  lab2_not_visible,       ///< a reading the record does not show
  lab2_absent,            ///< a term the fit left out
  lab2_bi_at,             ///< {value} {tau}
  lab2_range_end,
  lab2_process_wiener,  ///< the random-bias process
  lab2_process_gauss_markov,
  lab2_process_none,
  lab2_truth_both,         ///< {constant} {ramp}: the answer key when the runs differ
  lab2_q_systematic_bias,  ///< the table's quantities
  lab2_m_lab_constant,     ///< the table's methods
  lab2_not_meaningful,
  lab2_m_at_mean_temperature,
  lab2_at_temperature,  ///< {t}
  lab2_q_c1,
  lab2_m_polynomial,
  lab2_q_temperature_terms,
  lab2_m_criterion,
  lab2_criterion_cell,  ///< {degree}
  lab2_criterion_cell_none,
  lab2_t_barely_moves,
  lab2_degree_0_chosen,
  lab2_plus_minus,  ///< {half width}
  lab2_q_random_bias,
  lab2_m_model_choice,
  lab2_q_k,
  lab2_m_psd_k,
  lab2_m_allan_k,
  lab2_m_fit,
  lab2_q_gm_sigma,
  lab2_q_gm_tc,
  lab2_q_n,
  lab2_m_psd_n,
  lab2_m_allan_n,
  lab2_q_arw,
  lab2_m_arw,
  lab2_q_bias_instability,
  lab2_m_allan_minimum,
  lab2_q_class,
  lab2_m_class,
  lab2_class_cell,  ///< {class} {how decided}
  lab2_both_criteria,
  lab2_by_arw,
  lab2_by_bias_instability,
  lab2_change,  ///< {what} {before} {after} {unit} {percent}
  lab2_change_changed,
  lab2_change_unchanged,
  lab2_change_not_comparable,
  lab2_temperature_spans,  ///< {ramp span} {constant span}
  lab2_polynomial_moves,   ///< {degree} {range} {times the bias instability}
  lab2_no_dependence,
  lab2_verdict_term,  ///< {j} {value} {half width} {unit} {standard errors} {verdict}
  lab2_verdict_stands_out,
  lab2_verdict_in_noise,
  lab2_verdict_degree,  ///< {penalty} {degree}
  lab2_verdict_nothing_stands_out,
  lab2_bias_at_mean,  ///< {bias} {t} {bias} {t} {difference}
  lab2_bias_wander,   ///< {times} {wander}
  lab2_bias_end,
  lab2_bias_constant_not_meaningful,
  lab2_random_bias_differs,  ///< {constant} {ramp}
  lab2_random_bias_both,     ///< {process}
  lab2_random_bias_gm,       ///< {sigma before} {after} {Tc before} {after}
  lab2_k_symbol,             ///< the Wiener intensity in a sentence
  lab2_white_noise_fit,
  lab2_bias_instability_minimum,
  lab2_only_one_run,  ///< {run} {symbol} {value} {unit} {why}
  lab2_run_ramp,      ///< the run, in lab2_only_one_run
  lab2_run_constant,
  lab2_ramp_not_removed,
  lab2_class_same,     ///< {class}
  lab2_class_differs,  ///< {constant} {ramp}
  lab2_conclusion_unchanged,
  lab2_conclusion_changed,  ///< {list}
  lab2_and,                 ///< joins the last two items of a list
  lab2_changed_white,       ///< changed items
  lab2_changed_bias_instability,
  lab2_changed_k,
  lab2_changed_process,
  lab2_changed_term,  ///< {term}
  lab2_class_run,     ///< {class} {condition} {how decided}: one run in the class sentence
  lab2_class_at_constant,
  lab2_class_during_ramp,
  lab2_class_agree,
  lab2_class_decided_arw,
  lab2_class_decided_bi,
  lab2_col_quantity,  ///< the table's headings
  lab2_col_method,
  lab2_col_answer_key,
  lab2_table_heading,        ///< {gyro} {file}: the HTML table's heading
  lab2_accuracy_class_line,  ///< {class sentence}
  lab2_scale_factor_note,    ///< Table 1's scale-factor column: static data cannot tell; calibrate
  lab2_q_eq17,
  lab2_m_eq17,
  lab2_eq17_cell,      ///< {worst %} {tau} {inside} {compared}
  lab2_k_convention,   ///< K read the manual's way: {allan c} {allan r} {psd c} {psd r}
  lab2_gyros_heading,  ///< the closing part: {gyro} {gyro}
  lab2_gyros_value,    ///< {what} {g1} {a} {g2} {b} {unit} {g2} {ratio} {g1}
  lab2_gyros_apart,
  lab2_gyros_overlap,
  lab2_gyros_process,  ///< {process} {gyro} {process} {gyro}
  lab2_gyros_class,    ///< {gyro} {class} {gyro} {class}
  lab2_question_18,
  lab2_answer_slope,  ///< {span} {c1} {ci} {z} {stands} {range deg/h} {range / BI}
  lab2_answer_stands_out,
  lab2_answer_not_separated,
  lab2_answer_no_slope,
  lab2_answer_noise_unchanged,
  lab2_answer_noise_changed,  ///< {list}
  lab2_answer_general,
  lab2_conclusions,
  lab2_conclusion_widest,       ///< {g1} {g2} {what} {ratio} {g2} {g1}
  lab2_conclusion_temperature,  ///< {gyro} {|c1|} {|c1| other} {other gyro}
  lab2_ramp_changed,
  // ---- analyze's report ----
  an_eq17,        ///< the eq. (17) check's row
  an_eq17_value,  ///< {inside} {compared} {worst %} {tau} {half-widths}
  an_eq17_none,
  an_legend_eq17,
  an_manual_k,                  ///< {K/sqrt3} {K/2pi}: K read the manual's way
  an_manual_q,                  ///< {C = sqrt3 Q} {Q}
  an_not_visible,               ///< g(): no reading
  an_no_bound,                  ///< parameter_text(): no upper bound
  an_random_bias_wiener,        ///< random_bias_answer(): {K}
  an_random_bias_gauss_markov,  ///< random_bias_answer(): {sigma} {Tc}
  an_random_bias_none,          ///< random_bias_answer(): neither
  an_bandwidth_none,            ///< bandwidth_sentence(): none
  an_bandwidth_moving_average,  ///< {samples} {cut-off} {percent} {lag-1} {reduction}
  an_bandwidth_butterworth,     ///< {cut-off} {percent} {lag-1} {reduction}
  an_bandwidth_first_order,     ///< {time constant} {cut-off} {percent} {lag-1} {reduction}
  an_bandwidth_beyond_memory,   ///< {c samples} {stand-in cut-off} {reduction}
  an_bandwidth_shape_free,      ///< {taus left out}: follows a modelled kind's sentence
  an_bandwidth_shape_free_all,  ///< the same when no tau lies inside the filter's memory
  an_bandwidth_shape_free_n,    ///< {N of that fit}: follows either
  an_bandwidth_shape_decides,   ///< {percent}: follows it where the two N differ
  an_lines_none,                ///< lines_sentence(): none
  an_line,                      ///< one line: {frequency} {width} {rms} {peak ratio}
  an_line_slow,     ///< one line below 1 Hz: {frequency} {period} {width} {rms} {peak ratio}
  an_line_removed,  ///< a slow sinusoid taken out of the record: {frequency} {period}
                    ///< {amplitude} {rms} {peak ratio}
  an_line_removed_periodic,      ///< a periodic disturbance taken out: {frequency} {period} {rms}
                                 ///< {first's amplitude} {harmonics} {highest k} {peak ratio}
  an_lines_scale,                ///< {factor}: follows the lines
  an_lines_tail,                 ///< ends the lines' sentence
  an_drift_unchecked,            ///< stationarity_sentence(): a record too short for the check
  an_drift_steady,               ///< {tau from} {tau to} {blocks} {largest |z|} {threshold}
  an_drift_trend,                ///< {taus} {|z|} {last/first}
  an_class_both,                 ///< class_sentence(): which criterion decided
  an_class_by_arw,               ///< "decided by the angle random walk (the worse of the two)"
  an_class_by_bias_instability,  ///< "decided by the bias instability (the worse of the two)"
  an_class_sentence,             ///< {class} {decided} {BI} {its class} {ARW} {its class}
  an_class_strategic,            ///< the manual's Table 1 classes
  an_class_navigation,           ///< "navigation"
  an_class_intermediate,         ///< "intermediate"
  an_class_tactical,             ///< "tactical"
  an_class_consumer,             ///< "consumer"
  an_record_title,               ///< record_title(): {file} {channel}
  an_plots_off,                  ///< render_figures(): why there are no plots
  an_gnuplot_missing,            ///< {error}
  an_page_title,                 ///< html_document(report): {title}
  an_recording,                  ///< heading
  an_file,                       ///< row headings
  an_rate_channel,               ///< "rate channel"
  an_temperature_channel,        ///< "temperature channel"
  an_none,                       ///< no channel, no steps, ...
  an_input_unit,                 ///< "input unit"
  an_analysed_in,                ///< {unit}
  an_samples,                    ///< "samples"
  an_sample_rate,                ///< "sample rate"
  an_duration,                   ///< "duration"
  an_duration_value,             ///< {s} {h}
  an_systematic,                 ///< heading
  an_systematic_fit,             ///< {degree} {t_ref} {chosen} {fallback}
  an_degree_chosen,              ///< ", degree chosen by the criterion"
  an_constant_fallback_why,      ///< ", constant fallback (the temperature barely moves)"
  an_constant_fallback,          ///< ", constant fallback"
  an_coefficient,                ///< table headings
  an_standard_error,             ///< "standard error"
  an_systematic_bias,            ///< row headings
  an_lab_constant,               ///< "lab's polyfit(T, Y, 2) constant term"
  an_not_meaningful,             ///< " (not meaningful: the span is too small)"
  an_temperature_span,           ///< "temperature span"
  an_span_value,                 ///< {span} {min} {max}
  an_residual_rms,               ///< "residual rms"
  an_no_temperature_mean,        ///< {mean}
  an_no_temperature,             ///< "No temperature: only the record mean (the constant bias..."
  an_noise_model,                ///< heading
  an_terms_chosen,               ///< {terms} {points} {dispersion}
  an_fit,                        ///< {how the fit ended}
  an_parameter,                  ///< table headings
  an_meaning,                    ///< "meaning"
  an_status,                     ///< "status"
  an_status_resolved,            ///< a term's status
  an_status_upper_bound,         ///< "upper_bound"
  an_status_absent,              ///< "absent"
  an_sym_n,                      ///< the terms' symbols (the manual's: rho, q)
  an_sym_b,                      ///< "B"
  an_sym_k,                      ///< "K"
  an_sym_r,                      ///< "R"
  an_sym_q,                      ///< "Q"
  an_sym_gm,                     ///< "GM"
  an_param_gm_sigma,             ///< the Gauss-Markov parameters' names
  an_param_gm_tc,                ///< "gm_tc"
  an_meaning_n,                  ///< the parameters' meanings (core/noise_model.h)
  an_meaning_n_accel,            ///< an accelerometer's N
  an_meaning_b,                  ///< "flicker, bias instability coefficient (plateau 0.664 B)"
  an_meaning_k,                  ///< "rate random walk (Wiener process intensity)"
  an_meaning_r,                  ///< "rate ramp"
  an_meaning_q,                  ///< "angle quantisation"
  an_meaning_gm_sigma,           ///< "Gauss-Markov random bias, standard deviation"
  an_meaning_gm_tc,              ///< "Gauss-Markov random bias, correlation time"
  an_arw,                        ///< row headings
  an_vrw,                        ///< "velocity random walk (60 N)"
  an_bandwidth,                  ///< "sensor bandwidth"
  an_lines,                      ///< "spectral lines"
  an_drift,                      ///< "short-tau stationarity"
  an_steps,                      ///< "bias steps"
  an_steps_levelled,             ///< follows their count
  an_steps_as_noise,             ///< follows their count: left in as the bias's process
  an_left_in,                    ///< follows a count of steps or spikes
  an_spikes,                     ///< "spikes"
  an_spikes_value,               ///< {count} {threshold} {replaced or left in}
  an_heavy_tail,                 ///< {tail index} {threshold}
  an_spikes_replaced,            ///< ", replaced by that mean"
  an_quantisation,               ///< "output quantisation"
  an_quantisation_value,         ///< {lsb} {white level}
  an_quantisation_none,          ///< "none seen in the samples"
  an_bias_instability,           ///< "bias instability (ADEV minimum)"
  an_bias_instability_value,     ///< {value} {tau} {at the edge}
  an_at_edge_why,                ///< " (at the end of the tau range: the true minimum may lie..."
  an_readings,                   ///< heading
  an_quantity,                   ///< table headings
  an_adev_reading,               ///< "ADEV reading"
  an_psd_reading,                ///< "PSD reading"
  an_fit_interval,               ///< "fit (95 % interval)"
  an_reading_n,                  ///< rows
  an_reading_k,                  ///< "Wiener intensity K (ADEV at tau = 3 s on the +1/2 line;..."
  an_reading_bias_instability,   ///< "bias instability (ADEV minimum; fit: flicker B)"
  an_value_at,                   ///< {value} {tau}
  an_random_bias,                ///< heading
  an_random_bias_is,             ///< {random_bias_answer()}
  an_hypothesis,                 ///< table headings
  an_deviance,                   ///< "deviance"
  an_criterion,                  ///< "criterion"
  an_no_random_bias,             ///< rows
  an_wiener_process,             ///< "Wiener process"
  an_gauss_markov_process,       ///< "Gauss-Markov process"
  an_slopes,                     ///< {ADEV slope} {PSD slope}
  an_class,                      ///< heading
  an_class_accel,                ///< heading for an accelerometer
  an_no_accelerometer_class,     ///< report.h kNoAccelerometerClass
  an_notes,                      ///< heading
  an_md_recording,               ///< {file} {channel} {temperature} {samples} {rate} {hours} {gaps}
  an_md_gaps,                    ///< {gaps} {missing}
  an_md_systematic,              ///< heading
  an_md_polynomial,              ///< {degree} {t_ref} {chosen} {fallback}
  an_md_systematic_bias,         ///< {t_ref} {bias} {span}
  an_md_no_temperature_mean,     ///< {mean}
  an_md_no_temperature,          ///< "No temperature: only the record mean was removed."
  an_md_noise,                   ///< {terms}
  an_md_at_edge,                 ///< " (at the end of the tau range)"
  an_md_arw,                     ///< {ARW} {BI} {tau} {at the edge}
  an_md_vrw,                     ///< {VRW} {BI} {BI in mg} {tau} {at the edge}
  an_md_readings,                ///< {ADEV N} {ADEV K} {minimum} {PSD N} {PSD K}
  an_md_random_bias,             ///< "random bias"
  an_md_class,                   ///< "accuracy class"
  an_plot_gap,                   ///< legends: {count}
  an_plot_step,                  ///< {count}
  an_plot_step_as_noise,         ///< {count}: jumps left in as the bias's process
  an_plot_gap_jump,              ///< {count}
  an_plot_spike,                 ///< {count}
  an_plot_time,                  ///< plot title: {record}
  an_axis_time,                  ///< axis labels
  an_axis_rate,                  ///< "rate [deg/h]"
  an_axis_temperature,           ///< "temperature [degC]"
  an_legend_envelope,            ///< {samples}
  an_legend_block_mean,          ///< "rate, block mean"
  an_legend_rate,                ///< "rate"
  an_legend_temperature,         ///< "temperature (right axis)"
  an_legend_temperature_channel,  ///< {channel}
  an_plot_bias,                   ///< plot title: {record}
  an_axis_bias,                   ///< "bias (block mean of the rate) [deg/h]"
  an_legend_block_means_s,        ///< {seconds}
  an_legend_block_means,          ///< "block means"
  an_legend_polynomial,           ///< {degree} {t_ref} {fallback}
  an_source_psd,                  ///< where a line's level comes from
  an_source_fit,                  ///< "fit"
  an_plot_psd,                    ///< plot title: {record}
  an_axis_frequency,              ///< "frequency [Hz]"
  an_axis_sqrt_psd,               ///< "sqrt(PSD) [deg/h/sqrt(Hz)]"
  an_legend_welch_smoothed,       ///< "Welch estimate, log-smoothed"
  an_legend_welch,                ///< "Welch estimate"
  an_legend_line_band,            ///< {frequency} {rms}
  an_legend_line_removed_band,    ///< {frequency} {rms}: a sinusoid taken out of the record
  an_legend_periodic_band,        ///< {frequency} {rms}: a periodic disturbance taken out
  an_legend_white_level,          ///< {N} {source}
  an_legend_random_walk,          ///< {K} {source}
  an_plot_adev,                   ///< plot title: {record}
  an_axis_tau,                    ///< "tau [s]"
  an_axis_adev,                   ///< "Allan deviation [deg/h]"
  an_legend_bandwidth,            ///< "sensor bandwidth (white level lowered > 1 %)"
  an_legend_first_taus,           ///< {count}
  an_legend_oadev,                ///< "OADEV"
  an_legend_term_q,               ///< each term's line, with its slope
  an_legend_term_n,               ///< "white noise N (-1/2)"
  an_legend_term_b,               ///< "flicker B (0)"
  an_legend_term_k,               ///< "random walk K (+1/2)"
  an_legend_term_r,               ///< "rate ramp R (+1)"
  an_legend_term_gm,              ///< "Gauss-Markov sigma, Tc"
  an_legend_white_bandwidth,      ///< {cut-off}
  an_legend_line,                 ///< {frequency}
  an_legend_lines,                ///< {count}
  an_legend_fit,                  ///< {terms}
  an_legend_minimum,              ///< {BI} {tau}
  an_legend_drift,                ///< {blocks}: the taus allan_drift calls
  an_plot_drift,                  ///< plot title: {record}
  an_axis_drift_change,           ///< "change from the blocks' mean [%]"
  an_legend_drift_tau,            ///< {tau} {z} {last/first}: a tau allan_drift calls
  an_legend_drift_steady,         ///< {taus}: the taus checked and not called
  an_caption_time,                ///< figure captions
  an_caption_bias,                ///< "Bias (block means of the rate) against temperature, wit..."
  an_caption_psd,                 ///< "Square root of the two-sided PSD of the residual, log-l..."
  an_caption_adev,                ///< "Overlapping Allan deviation of the residual with its 95..."
  an_caption_drift,               ///< {blocks}
  // ---- the analyses' notes ----
  note_gaps,  ///< the record's gaps and how they were treated
  /// {taus} {from s} {to s} {share %}: Allan clusters that miss a few samples
  note_gap_clusters,
  /// {taus} {ratio range}: taus whose edf the Allan terms' own spread divided
  note_allan_terms_spread,
  note_step_item,  ///< one bias step: {size} at {time}
  note_steps,      ///< {count} {list} {threshold} {levelled or kept}
  note_steps_levelled,
  note_steps_kept,
  note_steps_as_noise,              ///< {why}: the jumps left in as the bias's process
  note_steps_beyond_limit,          ///< {limit}: more jumps than the search takes
  note_steps_wander,                ///< levelling them makes the record wander more
  note_steps_two_levels,            ///< they go back and forth between two levels
  note_steps_at_temperature_turns,  ///< {count} {turns}
  note_gap_jump_item,               ///< one jump across a gap: {size} {resumes at} {significance}
  note_gap_jumps,                   ///< {count} {list} {threshold}
  note_spikes,                      ///< {count} {threshold} {sds} {replaced or kept}
  note_spikes_replaced,
  note_spikes_kept,
  note_heavy_tail,  ///< {shoulder count} {Gaussian's} {alpha} {threshold} {excess kurtosis}
  /// {taus} {blocks} {|z|} {threshold} {last/first}, each a range_of / one_of
  note_allan_drift,
  range_of,  ///< {low} {high}: "low to high"
  one_of,    ///< {value}: the range of one value
  note_no_temperature,
  note_quantised,  ///< {lsb} {distinct} {examined} {level} {percent} {known or distorting}
  note_quantised_without_white,  ///< as note_quantised, no percent: no white noise resolved
  note_quantised_known,
  note_quantised_distorting,
  note_temperature_quantised,  ///< {lsb} {distinct} {changes} {mean hold s}
  note_temperature_kelvin,     ///< {lowest} {highest}: a temperature channel in kelvin?
  note_minimum_at_edge,        ///< {start or end} {tau}
  /// {lower deviation} {its tau} {the memory's end} {the reading} {its tau}
  note_minimum_inside_filter,
  word_start,           ///< the start (of a range)
  word_end,             ///< the end (of a range)
  note_fit_degenerate,  ///< {the fit's outcome}
  note_no_white,
  note_fit,  ///< {a sentence of the noise-model fit}
  fit_others_converged,
  fit_others_limited,       ///< {limited} {candidates}
  fit_converged,            ///< {terms} {iterations} {tolerance} {others}
  fit_iteration_limit,      ///< {terms} {iterations} {tolerance} {others}
  fit_degenerate,           ///< {points}
  fit_first_taus_left_out,  ///< {count} {first} {last} {from}
  fit_ramp_set_aside,       ///< {terms} {R} {low} {high} {span} {slope} {other terms} {supported}
  fit_gm_set_aside,         ///< {gm terms} {criterion} {against} {Tc} {low} {high} {factor} {bound}
                            ///< {wiener terms}
  temp_too_flat,            ///< {span} {min span} {degree asked}
  temp_degree_asked,        ///< {degree}: follows temp_too_flat
  temp_as_asked,            ///< {degree}
  temp_chosen,              ///< {degree} {penalty} {criteria} {top} {from degree}
  temp_chosen_from,         ///< {degree} {span}: follows temp_chosen
  ev_criteria,              ///< {none} {wiener} {gauss-markov}
  ev_wiener,                ///< {slope} {why} {criteria}
  ev_rw_best,
  ev_rw_explains,                 ///< {why the Gauss-Markov model was set aside}
  ev_gauss_markov,                ///< {Tc} {slope} {psd slope} {criteria}
  ev_none,                        ///< {slope} {criteria}
  cal_note_stretches_left_out,    ///< {count} {settle} {min samples}
  cal_note_plateaus_from_output,  ///< {count} {threshold}
  cal_note_plateau_left_out,      ///< {rate} {start} {samples} {settle} {min samples}
  cal_note_more_left_out,         ///< {more} {all}
  cal_note_alike_no_fit,          ///< {why}
  cal_note_alike_not_pd,
  cal_note_no_asymmetry,
  cal_note_degree_limited,  ///< {degree} {rates}
  table_note_no_edf,
  table_note_some_no_edf,  ///< {missing} {count}
  table_note_edf_from_counts,
  io_note_mat_integer,       ///< {file} {variable} {class} {wide}
  io_note_mat_integer_wide,  ///< follows io_note_mat_integer
  io_note_zero_stamps,       ///< {topic}
  io_note_duplicates,        ///< {dropped} {messages} {topic} {stamp source}
  io_stamp_header,           ///< the stamps' source
  io_stamp_receive,          ///< the stamps' source
  io_note_time_jitter,       ///< {file} {time} {irregular} {steps} {median step} {rms} {max} {rate}
  io_note_time_rows_dropped,  ///< {dropped} {rows} {time}
  io_note_time_bursts,        ///< {file} {time} {gaps} {present} {missing} {step}
  count_
};

/// The catalogue's text for `key` in `language` (never empty: a test checks both are whole),
/// with fmt placeholders for its numbers.
std::string_view text(Language language, Text key);

/// A sentence of the catalogue with the values of its placeholders, written in a language only
/// when it is shown. A value that is a Text is that key's own text in the same language (a
/// word or clause chosen by the code: "start" or "end"); a value that is a Message is that
/// sentence, and a std::vector<Message> those sentences joined by ", ", in the same language;
/// a NoiseTermSet is its terms' symbols (terms_text()).
struct Message {
  struct Nested {
    std::shared_ptr<const Message> message;
    friend bool operator==(const Nested& a, const Nested& b) { return *a.message == *b.message; }
  };
  struct List {  ///< messages joined by ", "
    std::shared_ptr<const std::vector<Message>> items;
    friend bool operator==(const List& a, const List& b) { return *a.items == *b.items; }
  };
  using Value = std::variant<long long, double, std::string, Text, Nested, List, NoiseTermSet>;
  Text key = Text::verbatim;
  std::vector<Value> values;

  Message() = default;  ///< empty: says nothing
  template <class... Args>
  explicit Message(Text k, Args&&... args) : key(k) {
    values.reserve(sizeof...(args));
    (values.push_back(value_of(std::forward<Args>(args))), ...);
  }
  /// A sentence that only exists in English (from a library foglab calls): shown as it is.
  static Message verbatim(std::string sentence);

  /// True for a default-made Message, which says nothing.
  [[nodiscard]] bool empty() const { return key == Text::verbatim && values.empty(); }
  /// The sentence in `language` ("" when empty).
  [[nodiscard]] std::string text(Language language = Language::en) const;

  friend bool operator==(const Message&, const Message&) = default;

 private:
  template <class T>
  static Value value_of(T&& v) {
    using U = std::remove_cvref_t<T>;
    if constexpr (std::is_same_v<U, Text> || std::is_same_v<U, NoiseTermSet>) {
      return Value(v);
    } else if constexpr (std::is_same_v<U, Message>) {
      return Value(Nested{std::make_shared<const Message>(std::forward<T>(v))});
    } else if constexpr (std::is_same_v<U, std::vector<Message>>) {
      return Value(List{std::make_shared<const std::vector<Message>>(std::forward<T>(v))});
    } else if constexpr (std::is_integral_v<U>) {
      return Value(static_cast<long long>(v));
    } else if constexpr (std::is_floating_point_v<U>) {
      return Value(static_cast<double>(v));
    } else {
      return Value(std::string(std::forward<T>(v)));
    }
  }
};

/// "low to high" (Text::range_of), or the one value (Text::one_of) when the
/// two print alike at three significant digits.
Message range_message(double low, double high);

/// The terms' symbols joined by '+': to_string(NoiseTermSet) in English ("N+B+K"), the
/// manual's symbols in Russian ("ρ+B+q"); "none" (нет) when empty.
std::string terms_text(NoiseTermSet terms, Language language);

/// The English text of each message, in order (what the JSON carries).
std::vector<std::string> english(const std::vector<Message>& messages);

}  // namespace foglab
