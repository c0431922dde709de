// foglab — text helpers shared by the one-recording report (report.cc) and
// the lab-2 report (lab2.cc). Not installed.
#pragma once

#include <fmt/format.h>

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "foglab/model/analysis.h"
#include "foglab/report/report.h"
#include "foglab/stats/allan_drift.h"

namespace foglab::report::detail {

/// text() with its fmt placeholders filled.
template <class... Args>
std::string say(Language language, Text key, Args&&... args) {
  return fmt::format(fmt::runtime(text(language, key)), std::forward<Args>(args)...);
}

// Colours (colour-blind-safe Okabe-Ito palette).
inline constexpr const char* kBlue = "#0072b2";
inline constexpr const char* kLightBlue = "#56b4e9";
inline constexpr const char* kOrange = "#e69f00";
inline constexpr const char* kGreen = "#009e73";
inline constexpr const char* kRed = "#d55e00";
inline constexpr const char* kPurple = "#cc79a7";
inline constexpr const char* kYellow = "#b8a000";
inline constexpr const char* kBlack = "#000000";
inline constexpr const char* kGrey = "#606060";

/// 4 significant digits; "-" for NaN or infinity.
std::string g(double v);
/// The same, "not visible" when there is no reading.
std::string g(const std::optional<double>& v, Language language);

/// Value and interval of a parameter as the reports show them: a resolved
/// term "v" and "[lo, hi]"; a term left out "< bound" and "[0, bound]".
struct ParameterText {
  std::string value, interval;
};
ParameterText parameter_text(const model::ParameterEstimate& p, Language language);

/// "a Wiener process (rate random walk), K = ... deg/h/sqrt(s)" etc.
std::string random_bias_answer(const model::AnalysisResult& r, Language language);
/// "not resolved ..." or "time constant ... s (first-order cut-off ... Hz) ...":
/// the sensor bandwidth the fit found, and whether the intervals span the fit
/// that assumes no filter kind (NoiseFitResult::shape_free_taus_left_out).
std::string bandwidth_sentence(const model::NoiseFitResult& fit, Language language);
/// "none found" or "20.2 Hz (2.85 Hz wide), 882 deg/h rms, ...": the lines.
std::string lines_sentence(const model::NoiseFitResult& fit, Language language);
/// "tactical (decided by ...; by bias instability ...; by ARW ...)".
std::string class_sentence(const model::AnalysisResult& r, Language language);
/// The name of a class of the manual's Table 1: "tactical", "тактический".
std::string class_name(AccuracyClass c, Language language);
/// The catalogue's key for the unit of kNoiseParameters[parameter] (core/noise_model.h).
Text parameter_unit(std::size_t parameter);
/// `text` in the units of `sensor`: in_sensor_units() (core/units.h) for English; for an
/// accelerometer's Russian text every °/ч becomes м/с², and the rate's random walk the
/// acceleration's.
std::string sensor_text(std::string_view text, Sensor sensor, Language language);

/// The short taus' stationarity check (stats/allan_drift.h) in a table cell
/// (English: the IMU and fleet tables): "0.02, 0.04 s (last/first 1.06 to
/// 1.18)", "none (z within ±2.31)" (no pipe: a Markdown cell), or "not
/// checked" (`checked` false).
std::string drift_cell(const stats::AllanDriftCalls& calls, bool checked);
/// The same for a record's own check.
std::string drift_cell(const stats::AllanDrift& d);
/// The taus the check called, joined by `separator` ("0.02, 0.04, 0.08").
std::string called_taus(const stats::AllanDriftCalls& c, std::string_view separator = ", ");

/// The report's title, else "file (channel)", else the file name.
std::string record_title(const ReportInput& input, Language language);

/// <td>/<th> with the text escaped.
std::string td(std::string_view text);
std::string th(std::string_view text);

/// A figure as HTML: <figure> with its SVG, or a warning saying why it was skipped, and its
/// caption.
std::string figure_html(const Figure& figure, Language language = Language::en);

/// The report pages' style sheet.
extern const char* const kCss;

/// A figure's name (also its SVG id prefix) and caption.
struct FigureSpec {
  std::string name;
  std::string caption;
};

struct RenderedFigures {
  std::vector<Figure> figures;  ///< one per plot, in order
  bool skipped = false;         ///< gnuplot missing or plots off
  std::string note;             ///< "The plots were skipped: ...", when skipped
};

/// Draws `plots` (each its own gnuplot, in parallel) as the figures
/// `specs` describe, ids prefixed with options.id_prefix + name + "_"; with
/// plots off or gnuplot missing every figure carries the reason instead.
RenderedFigures render_figures(const std::vector<Plot>& plots, const std::vector<FigureSpec>& specs,
                               const ReportOptions& options);

/// The names and captions of report_plots()' figures, in its order.
std::vector<FigureSpec> report_figure_specs(const model::AnalysisResult& result,
                                            const ReportInput& input, Language language);

}  // namespace foglab::report::detail
