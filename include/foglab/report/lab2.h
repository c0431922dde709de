// foglab — the report of lab 2 (the lab manual's lab 2, items
// 1.1-3.1 and "Содержание отчета"): for each gyro, a constant-temperature run
// (Y1, T1) and a 10 degC ramp run (Y2, T2), each analysed by model::analyze()
// and drawn by make_report(); then what the manual asks the student to hand
// in:
//   * the table of each gyro (item 2.4): the systematic bias (the lab's
//     polyfit(T, Y, 2) constant term, and the bias at the mean temperature),
//     the Wiener intensity K when present, the white-noise intensity N —
//     each read from the PSD and from the Allan deviation as the lab does,
//     beside the fitted value with its 95 % interval — and the bias
//     instability, for constant and varying temperature;
//   * the accuracy class of each gyro at constant and at varying
//     temperature (items 2.5 and "Анализ данных таблиц");
//   * a short written comparison of what the ramp changed (item 2.4: "Как
//     влияет изменение температуры на перечисленные выше характеристики");
//   * when the data were generated with a known truth, the answer key in a
//     column beside the estimates.
// The same rows give the HTML, Markdown and CSV forms.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "foglab/core/accuracy_class.h"
#include "foglab/model/analysis.h"
#include "foglab/report/report.h"
#include "foglab/sim/lab2_variants.h"

namespace foglab::report {

/// The lab's two runs of a gyro.
enum class Lab2Condition { constant, ramp };
/// "constant temperature" | "temperature ramp".
std::string_view to_string(Lab2Condition condition);
/// A run's title: "FOG1, constant temperature (FOG1_1.mat, Y1)", in `language`.
std::string lab2_run_title(std::string_view gyro, Lab2Condition condition, std::string_view file,
                           std::string_view channel, Language language = Language::en);

/// What a run should show, when the data were generated (sim/lab2_variants:
/// computed from the model, not estimated). NaN: not part of the truth.
struct Lab2Truth {
  RandomBiasProcess random_bias_process = RandomBiasProcess::none;
  double N = 0.0;                        ///< [deg/h/sqrt(Hz)]
  double K = 0.0;                        ///< [deg/h/sqrt(s)], NaN without a Wiener process
  double gm_sigma = 0.0;                 ///< [deg/h], NaN without a Gauss-Markov process
  double gm_tc = 0.0;                    ///< [s], NaN without a Gauss-Markov process
  double bias_instability_deg_h = 0.0;   ///< minimum of the model ADEV over the usable taus
  double bias_at_t_ref_deg_h = 0.0;      ///< the systematic bias at the reference temperature
  double lab_constant_term_deg_h = 0.0;  ///< the polynomial at 0 degC (the lab's p3)
  double c1_deg_h_per_c = 0.0;           ///< linear temperature coefficient
  AccuracyClass accuracy_class = AccuracyClass::consumer;
};

/// The truth of a generated run (sim/lab2_variants.h's answer key).
Lab2Truth lab2_truth(const sim::Lab2Gyro& gyro, const sim::Lab2Run& run);

/// One analysed run.
struct Lab2Run {
  std::string gyro;  ///< e.g. "FOG1": runs with the same name form one gyro's table
  Lab2Condition condition = Lab2Condition::constant;
  model::AnalysisResult result;
  ReportInput input;  ///< title, file, channels, preview (report.h)
  std::optional<Lab2Truth> truth;
};

/// One cell of the table: the number (NaN when there is none) and its text.
struct Lab2Cell {
  double value = 0.0;
  double ci95_low = 0.0, ci95_high = 0.0;  ///< NaN when there is no interval
  std::string text;                        ///< as shown, e.g. "0.0123 [0.0119, 0.0127]"
};

struct Lab2Row {
  std::string quantity;          ///< e.g. "white noise N"
  std::string method;            ///< e.g. "PSD: flat level", "Allan: -1/2 line at 1 s", "fit"
  std::string unit;              ///< e.g. "deg/h/sqrt(Hz)"
  std::array<Lab2Cell, 2> runs;  ///< constant, ramp (text "-" for a missing run)
  std::string truth;             ///< answer key text (empty: none)
};

/// One gyro's table, its classes and the comparison of its two runs.
struct Lab2Table {
  std::string gyro;
  Language language = Language::en;      ///< of every text below
  std::array<const Lab2Run*, 2> runs{};  ///< constant, ramp; null when not analysed
  std::vector<Lab2Row> rows;
  bool has_truth = false;
  /// "FOG1: intermediate at constant temperature, intermediate during the ramp".
  std::string class_sentence;
  /// What the ramp changed, a sentence per item (empty without both runs).
  std::vector<std::string> comparison;
};

/// The report's closing part (the manual's report contents: the analysis of
/// the tables and the conclusions), in the tables' language: two gyros
/// compared at constant temperature (each quantity with the ratio and
/// whether the 95 % intervals tell them apart), the manual's review question
/// on temperature answered with the run's numbers, and the conclusions.
struct Lab2Closing {
  std::string heading;                  ///< e.g. "FOG1 against FOG2"; empty: no two gyros
  std::vector<std::string> comparison;  ///< a sentence per quantity
  std::string temperature_question;     ///< review question 18 (empty without a ramp run)
  std::string temperature_answer;
  std::vector<std::string> conclusions;
};

/// The closing part of `tables` (the first two gyros with a constant-temperature run are
/// compared); everything empty when there is nothing to compare or conclude.
Lab2Closing lab2_closing(std::span<const Lab2Table> tables);

/// The tables of the gyros in `runs`, in order of first appearance. The
/// returned tables point into `runs`.
std::vector<Lab2Table> lab2_tables(std::span<const Lab2Run> runs, Language language = Language::en);

/// The tables, each with its class line, notes and the ramp's comparison,
/// then the closing part (lab2_closing()).
std::string lab2_tables_markdown(std::span<const Lab2Table> tables);
std::string lab2_tables_html(std::span<const Lab2Table> tables);
/// Long format: gyro, quantity, method, unit, condition, value, ci95_low,
/// ci95_high, truth (one line per cell), with a `#` comment line on top; in the tables'
/// language (make_lab2_report's CSV is always English).
std::string lab2_tables_csv(std::span<const Lab2Table> tables);

struct Lab2Report {
  std::vector<Report> runs;  ///< one per Lab2Run, in order
  std::vector<Lab2Table> tables;
  std::string html;              ///< the whole self-contained page
  std::string markdown_summary;  ///< tables, classes, comparisons (for the terminal)
  std::string markdown;          ///< the summary followed by every run's Markdown
  std::string csv;               ///< lab2_tables_csv(), in English
  bool plots_skipped = false;
  std::string plots_note;
};

/// Draws every run's plots (the runs in parallel, one gnuplot each) and
/// writes the page titled `title`, with `intro` (plain text) under it, in
/// options.language (core/language.h).
Lab2Report make_lab2_report(std::span<const Lab2Run> runs, std::string_view title,
                            std::string_view intro, const ReportOptions& options = {});

}  // namespace foglab::report
