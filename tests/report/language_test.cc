// The reports' languages (core/language.h): both catalogues whole and alike in their
// placeholders, and a Russian report with no English left in it (issue 20): every word of
// Latin letters in the page's text and its plots' text is a symbol, a standard's name or the
// program's.
#include "foglab/core/language.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/model/calibration.h"
#include "foglab/report/calibration.h"
#include "foglab/sim/rate_table.h"
#include "support/english_left.h"

namespace foglab::report {
namespace {

/// The text's fmt placeholders in order, with their format specs: "{}", "{:.4g}", ...
std::vector<std::string> placeholders(std::string_view text) {
  std::vector<std::string> found;
  const std::string s(text);
  const std::regex placeholder("\\{[^}]*\\}");
  for (auto it = std::sregex_iterator(s.begin(), s.end(), placeholder);
       it != std::sregex_iterator(); ++it) {
    found.push_back(it->str());
  }
  return found;
}

TEST(Language, BothCataloguesHoldEveryTextWithTheSamePlaceholders) {
  for (int k = 0; k < static_cast<int>(Text::count_); ++k) {
    const auto key = static_cast<Text>(k);
    const std::string_view en = text(Language::en, key), ru = text(Language::ru, key);
    EXPECT_FALSE(en.empty()) << "key " << k;
    EXPECT_FALSE(ru.empty()) << "key " << k;
    // The same values in the same order and formats: a Message's values fit both.
    EXPECT_EQ(placeholders(en), placeholders(ru)) << "key " << k << ": " << en << " | " << ru;
    // Every Russian text whose English has words (outside its placeholders) and that keeps a
    // Latin word says something in Cyrillic, but for a field's name (header.stamp).
    const std::string en_words = std::regex_replace(std::string(en), std::regex("\\{[^}]*\\}"), "");
    const bool has_words = std::regex_search(en_words, std::regex("[A-Za-z]{3,}"));
    const bool cyrillic =
        ru.find("\xD0") != std::string_view::npos || ru.find("\xD1") != std::string_view::npos;
    // (A symbol or a unit, "gm_sigma" as "σ", "degC" as "°C", has no Latin word left.)
    const bool latin_words = std::regex_search(std::string(ru), std::regex("[A-Za-z]{3,}"));
    if (has_words && latin_words && key != Text::io_stamp_header) {
      EXPECT_TRUE(cyrillic) << "key " << k << ": " << ru;
    }
  }
  EXPECT_EQ(language_from_string("RU"), Language::ru);
  EXPECT_THROW(language_from_string("de"), UsageError);
}

TEST(Language, ARussianCalibrationReportHasNoEnglishLeft) {
  sim::RateTableGyro g;
  g.scale_factor_temp_coefs = {-8e-5};
  g.nonlinearity_coefs = {4e-8, 1.5e-10};
  g.asymmetry = 2e-5;
  g.noise.N = 0.5;
  const std::vector<double> temperatures = {0.0, 40.0};
  const auto plan = sim::standard_rate_table_plan(300.0, 4, temperatures, 20.0);
  const sim::RateTableRecording r = sim::generate_rate_table(g, plan, {});
  const model::Calibration c =
      model::calibrate({r.sample_rate_hz, r.rate_command_deg_s, r.output_lsb, r.temperature_c});
  ASSERT_TRUE(c.notes.empty());  // notes come from the model, in English (not yet translated)
  ReportOptions options;
  options.language = Language::ru;
  const CalibrationReport rep = make_calibration_report(c, "stend.csv", options);
  // Latin words allowed: symbols of the model, the standard's and the program's names, the
  // file's, and gnuplot's own words (none when plots are drawn).
  const std::set<std::string> allowed = {"IEEE", "Std", "foglab", "sign", "sqrt", "stend", "csv"};
  for (const std::string* page : {&rep.html, &rep.markdown}) {
    for (const std::string& left : test::english_left(*page, allowed)) ADD_FAILURE() << left;
  }
  EXPECT_NE(rep.html.find("<html lang=\"ru\">"), std::string::npos);
  EXPECT_NE(rep.html.find("смещение нуля"), std::string::npos);
  EXPECT_NE(rep.html.find("масштабный коэффициент"), std::string::npos);
}

}  // namespace
}  // namespace foglab::report
