// Lab 1's report in Russian (`foglab lab1 --lang ru`, issue 20): the page, its Markdown and its
// plots' titles, axes and legends say everything in the lab manual's terms, with no English word
// left; the English report, the default, says what it said before.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <string>
#include <vector>

#include "foglab/core/language.h"
#include "foglab/report/lab1.h"
#include "foglab/report/plot.h"
#include "foglab/sim/lab1.h"
#include "support/english_left.h"
#include "support/files.h"

namespace foglab::report {
namespace {

// Latin words a Russian lab-1 page may show, each a name or a symbol, not English:
//   foglab       the program's name (the footer);
//   IEEE, Std    the standard's name (the footer's "IEEE Std 952");
//   sin, cos     the functions of the manual's formulas (S = 2γ sin φ_s, γ (1 + cos φ));
//   sinc         sin(x)/x, in the analytic nonlinearity's formula.
// Two-letter symbols (K_s, n_g, f_m, J1, the manual's "I vs fi" and "S vs Om") are below the
// three letters english_left() looks at.
// ... and the option that shows the manual's form and the notes' file name.
const std::set<std::string> kAllowed = {"foglab", "IEEE",  "Std",  "sin",    "cos",  "sinc",
                                        "output", "phase", "docs", "manual", "notes"};

class Lab1Language : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { result_ = new sim::Lab1Result(sim::run_lab1(sim::lab1_coil(1))); }
  static void TearDownTestSuite() {
    delete result_;
    result_ = nullptr;
  }
  static const sim::Lab1Result& result() { return *result_; }

  static Lab1Report report(Language language, bool plots) {
    ReportOptions options;
    options.language = language;
    options.plots = plots;
    options.title_block = {1, 1, "Петров П.", "R3241", "2026-11-27"};  // issue 23's title page
    const std::string title = fmt::format(fmt::runtime(text(language, Text::lab1_title)), 1);
    return make_lab1_report(result(), title, {}, options);
  }

 private:
  static inline sim::Lab1Result* result_ = nullptr;
};

TEST_F(Lab1Language, RussianReportHasNoEnglishLeftInItsTextOrPlots) {
  const bool plots = gnuplot_available();
  const Lab1Report rep = report(Language::ru, plots);
  std::string html = rep.html, markdown = rep.markdown;
  if (rep.plots_skipped) {
    // gnuplot could not run: its reason is report.cc's, not this report's; the page's own text
    // is still checked, and the plots' text by PlotsSpeakRussian.
    html = std::regex_replace(html, std::regex("<p class=\"warn\">[^<]*</p>"), " ");
    const std::size_t note = markdown.find(rep.plots_note);
    ASSERT_NE(note, std::string::npos);
    markdown.erase(note, rep.plots_note.size());
  } else {
    // Every plot drawn, so its SVG <text> (titles, axes, legends) is checked too.
    EXPECT_EQ(test::occurrences(html, "<svg"), 11u);
    EXPECT_NE(html.find(">действующая угловая скорость [°/с]<"), std::string::npos);
    EXPECT_NE(html.find(">разность фаз модуляции (правая ось)<"), std::string::npos);
  }
  for (const std::string* page : {&html, &markdown}) {
    for (const std::string& left : test::english_left(*page, kAllowed)) ADD_FAILURE() << left;
  }
  EXPECT_NE(rep.html.find("<html lang=\"ru\">"), std::string::npos);
  EXPECT_NE(markdown.find("# Лабораторная работа № 1: вариант 1\n"), std::string::npos);
  // The title page and the aim, before the first section.
  for (const std::string* page : {&html, &markdown}) {
    for (const char* part : {"Университет ИТМО", "Лабораторная работа 1: Исследование линейности",
                             "Вариант 1", "Петров П.", "R3241", "Цель работы"}) {
      EXPECT_NE(page->find(part), std::string::npos) << part;
    }
    EXPECT_LT(page->find("Цель работы"), page->find("фаза Саньяка"));
  }
  // The manual's terms.
  for (const char* term : {"фаза Саньяка", "сигнал демодуляции", "масштабный коэффициент",
                           "Нелинейность выходной характеристики", "Открытая схема",
                           "Схема с обратной связью", "фотоприёмник", "меандр",
                           "частота фазовой модуляции f_m", "Ω_π/2", "°/с", "кГц", "Выводы"}) {
    EXPECT_NE(html.find(term), std::string::npos) << term;
    EXPECT_NE(markdown.find(term), std::string::npos) << term;
  }
  // The numbers are the same as in English: the square sweep's nonlinearity.
  const std::string nonlinearity =
      fmt::format("{:.3f} %", result().sweep_square.nonlinearity_percent);
  EXPECT_NE(markdown.find("±Ω_π/2: " + nonlinearity), std::string::npos) << nonlinearity;
}

TEST_F(Lab1Language, PlotsSpeakRussian) {
  // The plot descriptions alone, whether or not gnuplot is installed.
  const std::vector<Plot> plots = lab1_plots(result(), Language::ru);
  ASSERT_EQ(plots.size(), 11u);
  std::string all;
  int legends = 0;
  for (const Plot& p : plots) {
    EXPECT_FALSE(p.title.empty());
    EXPECT_FALSE(p.x_label.empty());
    all += p.title + "\n" + p.x_label + "\n" + p.y_label + "\n" + p.y2_label + "\n";
    for (const Series& s : p.series) {
      all += s.title + "\n";
      legends += s.title.empty() ? 0 : 1;
    }
  }
  EXPECT_GE(legends, 20);
  for (const std::string& left : test::english_left(all, kAllowed)) ADD_FAILURE() << left;
  EXPECT_EQ(plots[1].x_label, "действующая угловая скорость [°/с]");
  EXPECT_NE(all.find("прямоугольная модуляция"), std::string::npos);
  EXPECT_NE(all.find("синусоидальная модуляция"), std::string::npos);
  EXPECT_NE(all.find("без модуляции"), std::string::npos);
}

TEST_F(Lab1Language, EnglishStaysTheDefaultAndSaysWhatItSaid) {
  const std::vector<Plot> plots = lab1_plots(result());
  ASSERT_EQ(plots.size(), 11u);
  EXPECT_EQ(plots[1].title, "Demodulated output against rate (S vs Om), open loop");
  EXPECT_EQ(plots[0].series[1].title, "no modulation");
  EXPECT_EQ(plots[1].series[0].title, "no modulation, time simulation");
  EXPECT_EQ(plots[10].title, "Square modulation at 0.5 f_m: transition spikes");
  ReportOptions options;
  options.plots = false;
  const Lab1Report rep = make_lab1_report(result(), "foglab lab 1: variant 1", {}, options);
  EXPECT_NE(rep.html.find("<html lang=\"en\">"), std::string::npos);
  for (const char* said :
       {"# foglab lab 1: variant 1\n", "## The coil (item 1.1)\n", "| quantity | value | unit |\n",
        "| range Omega_pi/2 | 148.508 | deg/s |\n",
        "## Open loop, sine modulation (phi_m = 1.8 rad): the sweep\n",
        "| rate [deg/s] | S [a.u.] | SF [a.u. per deg/s] |\n", "## Conclusions\n",
        "- Without modulation the detector gives gamma (1 + cos phi_s): flat at zero rate"}) {
    EXPECT_NE(rep.markdown.find(said), std::string::npos) << said;
  }
  EXPECT_NE(rep.html.find("Square modulation away from the proper frequency."), std::string::npos);
  // No Cyrillic in the English page.
  EXPECT_EQ(rep.html.find("\xD0"), std::string::npos);
  EXPECT_EQ(rep.markdown.find("\xD1"), std::string::npos);
  // The sweeps' CSV, an interface, is the same in either language.
  EXPECT_EQ(report(Language::ru, false).sweep_csv, rep.sweep_csv);
}

}  // namespace
}  // namespace foglab::report
