// foglab — the report of one analysed recording: plots, a self-contained
// HTML page, a Markdown summary and Kalibr's imu.yaml.
//
// Input: the analysis (model/analysis.h) plus what it does not keep — the
// record's name, channels and units, and a decimated copy of the rate and
// temperature for the time plots (preview_record(): block means with the
// block minimum and maximum as an envelope, ~2000 blocks, made before
// analyze() consumes the rate, so a 10^9-sample record costs one pass and no
// second copy).
//
// Plots (gnuplot, plot.h), each with units on every axis and a legend:
//   1. rate [deg/h] (block means and min/max envelope) and temperature
//      [degC] (right-hand axis) against time [h];
//   2. bias against temperature: block means of the rate against block means
//      of the temperature, with the fitted polynomial sum c_j (T - t_ref)^j
//      (systematic.h) over the temperature span (only with a temperature);
//   3. sqrt of the two-sided PSD of the residual [deg/h/sqrt(Hz)] against
//      frequency [Hz], log-log with equal decades: Welch estimate
//      log-smoothed, the white-noise level N read off the flat part and the
//      random-walk line K/(2 pi f) read off the -2 slope (readings.h);
//   4. the overlapping Allan deviation [deg/h] against tau [s], log-log with
//      equal decades: the estimate with its 95 % band, the fitted model
//      sqrt(AVAR(tau)) (noise_fit.h) and the line of each term present, and
//      the minimum (bias instability).
// The model curve is the model's own Allan deviation; the fit compared the
// residual's Allan variance with the model times the factors for what
// removing the temperature polynomial did to each term (analysis.h), so at
// the longest taus of a ramp run the curve may lie slightly above the data.
//
// Kalibr (https://github.com/ethz-asl/kalibr/wiki/IMU-Noise-Model) wants the
// continuous-time gyroscope noise density in rad/s/sqrt(Hz) and the bias
// random walk in rad/s^2/sqrt(Hz):
//   gyroscope_noise_density = N [deg/h/sqrt(Hz)] * (pi/180) / 3600,
//   gyroscope_random_walk   = K [deg/h/sqrt(s)]  * (pi/180) / 3600
// (1/sqrt(s) = sqrt(Hz), so rad/s/sqrt(s) = rad/s^2/sqrt(Hz)). When the
// record does not resolve K, its 95 % upper bound is written and a comment
// says so.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "foglab/core/units.h"
#include "foglab/model/analysis.h"
#include "foglab/core/language.h"
#include "foglab/report/plot.h"

namespace foglab::report {

/// A decimated copy of a record for the time and bias-temperature plots.
struct RecordPreview {
  std::int64_t block_samples = 1;       ///< samples per block (the last may hold fewer)
  std::vector<double> time_s;           ///< [s] centre of each block
  std::vector<double> rate_mean_deg_h;  ///< [deg/h] block mean
  std::vector<double> rate_min_deg_h;   ///< [deg/h] block minimum
  std::vector<double> rate_max_deg_h;   ///< [deg/h] block maximum
  std::vector<double> temperature_c;    ///< [degC] block mean (empty without temperature)
};

/// Block means (and the rate's min/max) of a record sampled at
/// `sample_rate_hz`, about `points` blocks (every sample when the record is
/// shorter). `temperature_c` is empty or as long as the rate. Non-finite
/// samples are skipped. Throws UsageError for a non-positive sample rate,
/// mismatched lengths or points < 1.
/// With `gaps` (core/gaps.h) the times count the missing samples, blocks
/// stop at each gap and a point without values sits in it (no line crosses
/// a gap).
RecordPreview preview_record(std::span<const double> rate_deg_h,
                             std::span<const double> temperature_c, double sample_rate_hz,
                             std::size_t points = 2000, std::span<const Gap> gaps = {});

/// What the analysis does not keep about the recording.
struct ReportInput {
  std::string title;                 ///< heading, e.g. "FOG1, constant temperature"; empty: file
  std::string file_name;             ///< the recording as given
  std::string channel;               ///< rate channel, e.g. "Y1"
  std::string temperature_channel;   ///< e.g. "T1"; empty: no temperature
  std::string input_unit = "deg/h";  ///< the unit the rate was read in (converted to deg/h)
  /// An accelerometer's report speaks in m/s^2 (core/units.h
  /// in_sensor_units()), gives the velocity random walk in place of the
  /// angle random walk, and no Table 1 class (a table of gyroscopes).
  Sensor sensor = Sensor::gyroscope;
  RecordPreview preview;  ///< from preview_record() of the raw record
  /// [deg/h] the constant bias removed when there is no temperature (the
  /// analysis does not keep it).
  std::optional<double> record_mean_deg_h;
  std::vector<Message> notes;  ///< the caller's notes (shown with the analysis's)
};

/// The title page the manual asks of a lab report (its section on reports:
/// the lab's number and title, the variant, the student's name and group),
/// with the university and the date, followed by the aim of the work.
/// Fields left empty are left out; lab 0: no title block.
struct TitleBlock {
  int lab = 0;  ///< 1 or 2
  std::optional<int> variant;
  std::string student, group;
  std::string date;  ///< as given, e.g. "2026-11-27"
};

/// The title block and the aim as HTML (a <div class="title-block">, then
/// the aim under its heading) and as Markdown; empty for lab 0.
std::string title_block_html(const TitleBlock& block, Language language);
std::string title_block_markdown(const TitleBlock& block, Language language);

struct ReportOptions {
  bool plots = true;               ///< false: no gnuplot at all (the report says so)
  PlotOptions plot;                ///< the gnuplot executable, size, font
  std::string id_prefix = "r";     ///< SVG id prefix (distinct per report inlined in one page)
  std::size_t bias_points = 200;   ///< block means in the bias-temperature plot
  std::string rostopic = "/imu0";  ///< for imu.yaml
  /// The text's language (core/language.h): make_report()'s page, plots and Markdown;
  /// reports not yet converted (imu.h) ignore it.
  Language language = Language::en;
  TitleBlock title_block;  ///< the labs' reports: their title page and aim
  /// Lab 1: the closed loop's table in the manual's form (the feedback phase
  /// [rad], scale factor -K_s [s]) instead of foglab's rate (deg/s, 1).
  bool loop_output_phase = false;
};

/// One figure: its SVG, or why it is missing.
struct Figure {
  std::string name;  ///< "time", "bias_temperature", "psd", "adev", "allan_drift"
  std::string caption;
  std::optional<std::string> svg;  ///< inline <svg> element
  std::string error;               ///< empty when drawn
};

struct Report {
  std::string title;
  /// In the order above: no bias plot without a temperature, the drift
  /// plot only when allan_drift calls a tau.
  std::vector<Figure> figures;
  bool plots_skipped = false;   ///< gnuplot missing or plots off
  std::string plots_note;       ///< the sentence saying why, when skipped
  std::string html_section;     ///< <section>…</section> for html_document()
  std::string markdown;         ///< Markdown summary (for the terminal)
  std::string kalibr_yaml;      ///< imu.yaml (English, as Kalibr's file)
  /// The language of its text (ReportOptions::language); html_document() follows it.
  Language language = Language::en;
};

/// Draws the plots and writes every text form of the report.
Report make_report(const model::AnalysisResult& result, const ReportInput& input,
                   const ReportOptions& options = {});

/// The plot descriptions alone (no gnuplot run), in the figures' order.
std::vector<Plot> report_plots(const model::AnalysisResult& result, const ReportInput& input,
                               const ReportOptions& options = {});

/// A complete, self-contained HTML page (inline CSS and SVG, no external
/// resources) holding the sections of `reports` (lab 2: four of them), each
/// in a <div id="recording-k"> (k = 1, 2, ...) that a list of links at the
/// top points to when there are several; `preface_html` goes between that
/// list and the sections (lab 2: its summary tables).
std::string html_document(std::span<const Report> reports, std::string_view title,
                          std::string_view preface_html = {}, Language language = Language::en);
/// One report's page, in the report's language.
std::string html_document(const Report& report);

/// The Markdown summary alone.
std::string markdown_summary(const model::AnalysisResult& result, const ReportInput& input,
                             Language language = Language::en);

/// Kalibr's imu.yaml for the gyroscope (no accelerometer fields: they are
/// commented out), update_rate = the sample rate.
std::string kalibr_imu_yaml(const model::AnalysisResult& result, const ReportInput& input,
                            std::string_view rostopic = "/imu0");

/// N [deg/h/sqrt(Hz)] -> [rad/s/sqrt(Hz)].
constexpr double noise_density_rad_s_sqrt_hz(double n_deg_h_sqrt_hz) {
  return n_deg_h_sqrt_hz / kDegPerRad / kSecondsPerHour;
}
/// K [deg/h/sqrt(s)] -> [rad/s^2/sqrt(Hz)].
constexpr double random_walk_rad_s2_sqrt_hz(double k_deg_h_sqrt_s) {
  return k_deg_h_sqrt_s / kDegPerRad / kSecondsPerHour;
}

/// N [m/s^2/sqrt(Hz)] -> velocity random walk [m/s/sqrt(h)]: sqrt(3600 s/h) = 60.
constexpr double velocity_random_walk_m_s_sqrt_h(double n_m_s2_sqrt_hz) {
  return n_m_s2_sqrt_hz * 60.0;
}

/// What the reports say in place of an accelerometer's class.
inline constexpr std::string_view kNoAccelerometerClass =
    "none: the lab manual's Table 1 classes gyroscopes only (by bias instability and angle "
    "random walk); it does not apply to an accelerometer";

/// `text` with &, <, >, " and ' escaped for HTML.
std::string html_escape(std::string_view text);

}  // namespace foglab::report
