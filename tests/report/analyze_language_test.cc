// The report of one analysed recording in Russian (issue 20, `analyze --report --lang ru`):
// the page, its plots and the Markdown summary in the lab manual's terms and units with no
// English word left, and English still the default, word for word.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "foglab/core/language.h"
#include "foglab/core/noise_model.h"
#include "foglab/model/analysis.h"
#include "foglab/report/plot.h"
#include "foglab/report/report.h"
#include "foglab/sim/generator.h"
#include "support/english_left.h"

namespace foglab::report {
namespace {

/// Two hours at 10 Hz under a 10 degC ramp: white noise, flicker, a random walk, angle
/// quantisation and a linear temperature sensitivity, analysed once.
struct AnalysedRamp {
  model::AnalysisResult result;
  ReportInput input;
};

const AnalysedRamp& analysed_ramp() {
  static const AnalysedRamp a = [] {
    sim::ErrorModel m;
    m.noise.N = 0.5;
    m.noise.B = 0.05;
    m.noise.K = 0.005;
    m.noise.Q = 0.5;
    m.bias = 3.0;
    m.temp_coefs = {0.8};
    sim::TemperatureProfile t;
    t.kind = sim::TemperatureKind::ramp;
    t.start_c = 20.0;
    t.span_c = 10.0;
    t.jitter_c = 0.01;
    sim::GeneratorOptions g;
    g.sample_rate_hz = 10.0;
    g.duration_s = 7200.0;
    g.seed = 5;
    sim::Recording rec = sim::generate(m, t, g);
    AnalysedRamp out;
    out.input.file_name = "ВОГ1.mat";
    out.input.channel = "Y2";
    out.input.temperature_channel = "T2";
    out.input.preview = preview_record(rec.rate_deg_h, rec.temperature_c, rec.sample_rate_hz);
    out.result = model::analyze(rec.rate_deg_h, rec.temperature_c, rec.sample_rate_hz);
    return out;
  }();
  return a;
}

TEST(AnalyzeLanguage, ARussianReportHasNoEnglishLeft) {
  const AnalysedRamp& a = analysed_ramp();
  ReportOptions options;
  options.language = Language::ru;
  options.plots = gnuplot_available();  // drawn when it can be: the SVGs' text is checked too
  const Report rep = make_report(a.result, a.input, options);
  const std::string html = html_document(rep);
  if (options.plots) {
    ASSERT_FALSE(rep.plots_skipped) << rep.plots_note;
    EXPECT_EQ(test::occurrences(html, "<svg"), 4u);
  }
  // Latin words allowed: the standard's and the program's names, the MATLAB function the
  // manual's lab 2 calls (polyfit(T, Y, 2)), and the recording's file extension.
  // ... and the notes on the manual the convention lines cite (docs/manual_notes.md).
  const std::set<std::string> allowed = {"IEEE", "Std",  "foglab", "polyfit",
                                         "mat",  "docs", "manual", "notes"};
  // The analyses' notes included (core/language.h's Message): there must be some to check.
  ASSERT_FALSE(a.result.notes.empty());
  for (const std::string* page : {&html, &rep.markdown}) {
    for (const std::string& left : test::english_left(*page, allowed)) ADD_FAILURE() << left;
  }
  for (const Message& n : a.result.notes) {
    EXPECT_NE(html.find(html_escape(n.text(Language::ru))), std::string::npos) << n.text();
  }
  EXPECT_NE(html.find("<html lang=\"ru\">"), std::string::npos);
  EXPECT_NE(html.find("<title>Отчёт foglab: ВОГ1.mat (канал Y2)</title>"), std::string::npos);
  // The manual's terms, in the page and in the summary.
  for (const std::string& page : {html, rep.markdown}) {
    for (const std::string term : {"нестабильность смещения нуля", "случайное блуждание угла",
                                   "ласс точности", "девиации Аллана", "°/ч", "°/√ч"}) {
      EXPECT_NE(page.find(term), std::string::npos) << term;
    }
  }
  for (const std::string term : {"вариации Аллана", "белый шум", "винеровского процесса",
                                 "экспоненциально-коррелированный процесс", "шум квантования",
                                 "спектральной плотности мощности (СПМ)",
                                 "температурная зависимость", "°/ч/√Гц", "°/ч/√с"}) {
    EXPECT_NE(html.find(term), std::string::npos) << term;
  }
  if (options.plots) {
    EXPECT_NE(html.find("интервал осреднения τ [с]"), std::string::npos);
  }
  // The class by its name in the manual's Table 1.
  const AccuracyClass c = a.result.verdict.accuracy_class;
  const std::string name = c == AccuracyClass::strategic      ? "стратегический"
                           : c == AccuracyClass::navigation   ? "навигационный"
                           : c == AccuracyClass::intermediate ? "средний"
                           : c == AccuracyClass::tactical     ? "тактический"
                                                              : "потребительский";
  EXPECT_NE(html.find("<p class=\"verdict\">" + name + " ("), std::string::npos) << name;
  EXPECT_NE(rep.markdown.find("класс точности: **" + name + " ("), std::string::npos) << name;
  // The manual's symbols: rho for the white noise, q for the Wiener process.
  EXPECT_NE(html.find("<td>ρ</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>q</td>"), std::string::npos);
  EXPECT_NE(rep.markdown.find("| ρ |"), std::string::npos);
}

TEST(AnalyzeLanguage, ARussianAccelerometerReportSpeaksInItsUnits) {
  // The same analysis as an accelerometer's: every °/ч of the section and the summary
  // becomes м/с² (the page's footer names the gyroscope's units, as the English one does).
  const AnalysedRamp& a = analysed_ramp();
  ReportInput in = a.input;
  in.sensor = Sensor::accelerometer;
  in.input_unit = "m/s^2";
  ReportOptions options;
  options.language = Language::ru;
  options.plots = false;
  const Report rep = make_report(a.result, in, options);
  for (const std::string* section : {&rep.html_section, &rep.markdown}) {
    const std::string& page = *section;
    EXPECT_EQ(page.find("°/ч"), std::string::npos) << page;
    EXPECT_EQ(page.find("случайное блуждание угла"), std::string::npos) << page;
    EXPECT_EQ(page.find("°/√ч"), std::string::npos) << page;
    EXPECT_NE(page.find("м/с²"), std::string::npos);
    EXPECT_NE(page.find("случайное блуждание скорости"), std::string::npos);
  }
  EXPECT_NE(rep.html_section.find("к акселерометру она не применяется"), std::string::npos);
  for (const Plot& p : report_plots(a.result, in, options)) {
    EXPECT_EQ(p.y_label.find("°/ч"), std::string::npos) << p.y_label;
  }
}

TEST(AnalyzeLanguage, EnglishIsTheDefaultAndKeepsItsWords) {
  const AnalysedRamp& a = analysed_ramp();
  ReportOptions plain;
  plain.plots = false;
  ReportOptions english = plain;
  english.language = Language::en;
  const Report by_default = make_report(a.result, a.input, plain);
  const Report asked = make_report(a.result, a.input, english);
  EXPECT_EQ(by_default.html_section, asked.html_section);
  EXPECT_EQ(by_default.markdown, asked.markdown);
  EXPECT_EQ(markdown_summary(a.result, a.input), markdown_summary(a.result, a.input, Language::en));
  const std::string html = html_document(by_default);
  EXPECT_NE(html.find("<html lang=\"en\">"), std::string::npos);
  EXPECT_NE(html.find("<title>foglab report: ВОГ1.mat (Y2)</title>"), std::string::npos);
  // The parameters' meanings are core/noise_model.h's own, the class its to_string().
  for (const NoiseParameter& p : kNoiseParameters) {
    EXPECT_NE(html.find("<td>" + html_escape(p.meaning) + "</td>"), std::string::npos) << p.meaning;
  }
  EXPECT_NE(html.find("<p class=\"verdict\">" +
                      std::string(to_string(a.result.verdict.accuracy_class)) + " ("),
            std::string::npos);
  EXPECT_NE(by_default.markdown.find("| upper_bound |"), std::string::npos);
  // The JSON's accelerometer sentence (report.h) is the catalogue's English.
  EXPECT_EQ(text(Language::en, Text::an_no_accelerometer_class), kNoAccelerometerClass);
  EXPECT_NE(html.find("plotting was turned off"), std::string::npos);
  // The plots' words.
  const std::vector<Plot> plots = report_plots(a.result, a.input);
  ASSERT_EQ(plots.size(), 4u);
  EXPECT_EQ(plots[0].y_label, "rate [deg/h]");
  EXPECT_EQ(plots[3].x_label, "tau [s]");
  EXPECT_EQ(plots[3].title, "ВОГ1.mat (Y2): overlapping Allan deviation of the residual");
}

}  // namespace
}  // namespace foglab::report
