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

#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

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
  cal_title,            ///< "foglab calibrate: {run}"
  cal_triad_title,      ///< "foglab calibrate, a triad: {runs}"
  cal_section,          ///< "Calibration"
  cal_run,              ///< {plateaus} {temperatures} {full scale} {T_ref}: the run and eq. (10)
  cal_coefficient,      ///< table heading
  cal_row_s,            ///< S
  cal_row_sk,           ///< s_{k}
  cal_row_ak,           ///< a_{k}
  cal_row_a,            ///< A
  cal_row_u0,           ///< u0
  cal_row_u0_rate,      ///< u0 as a rate
  cal_row_bk,           ///< b_{k}
  unit_lsb_per_deg_s,   ///< LSB/(deg/s)
  unit_ppm_per_degc_k,  ///< ppm/degC^{k}
  unit_ppm_fs,          ///< ppm of full scale
  unit_ppm,             ///< ppm
  unit_lsb,             ///< LSB
  unit_deg_h,           ///< deg/h
  unit_lsb_per_degc_k,  ///< LSB/degC^{k}
  cal_nonlinearity,     ///< {ieee} {lab1} {degree}
  cal_noise,            ///< {N} {ARW} {rms} {dof}
  cal_weighting_noise,  ///< {N} {B} {K} {gm sigma} {gm Tc} {chi2}
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
  // ---- lab 2's report ----
  // ---- analyze's report ----
  // ---- the analyses' notes ----
  count_
};

/// The catalogue's text for `key` in `language` (never empty: a test checks both are whole),
/// with fmt placeholders for its numbers.
std::string_view text(Language language, Text key);

/// A sentence of the catalogue with the values of its placeholders, written in a language only
/// when it is shown. A value that is a Text is that key's own text in the same language (a
/// word or clause chosen by the code: "start" or "end").
struct Message {
  using Value = std::variant<long long, double, std::string, Text>;
  Text key{};
  std::vector<Value> values;

  Message() = default;
  template <class... Args>
  explicit Message(Text k, Args&&... args) : key(k) {
    values.reserve(sizeof...(args));
    (values.push_back(value_of(std::forward<Args>(args))), ...);
  }
  /// A sentence that only exists in English (from a library foglab calls): shown as it is.
  static Message verbatim(std::string sentence);

  /// The sentence in `language`.
  [[nodiscard]] std::string text(Language language = Language::en) const;

  friend bool operator==(const Message&, const Message&) = default;

 private:
  template <class T>
  static Value value_of(T&& v) {
    using U = std::remove_cvref_t<T>;
    if constexpr (std::is_same_v<U, Text>) return Value(v);
    else if constexpr (std::is_same_v<U, bool>) return Value(static_cast<long long>(v));
    else if constexpr (std::is_integral_v<U>) return Value(static_cast<long long>(v));
    else if constexpr (std::is_floating_point_v<U>) return Value(static_cast<double>(v));
    else return Value(std::string(std::forward<T>(v)));
  }
};

/// The English text of each message, in order (what the JSON carries).
std::vector<std::string> english(const std::vector<Message>& messages);

}  // namespace foglab
