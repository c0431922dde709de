// The lab reports opened in a real browser (issues 5 and 6): headless
// Chromium loads the page `foglab lab2` (or `lab1`) writes, and a script added to a copy of it
// measures every figure's SVG as laid out — its size on the page and how
// many of its drawn elements (lines, text) have a non-empty box. A page
// whose SVG did not parse, or whose plots are empty, fails. A screenshot of
// the page must also carry far more ink (PNG bytes) than one of a blank page
// (the page is not blank as rendered): checked on the lab-2 report and on
// analyze's, since every report takes the one style sheet of report.cc
// (each Chromium run costs about 3 s).
//
// Needs Debian's `chromium` (installed by scripts/install-deps.sh --tests).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli.h"
#include "support/files.h"

namespace foglab {
namespace {

namespace fs = std::filesystem;

/// The measuring script: one line per figure SVG, "width height elements inked".
constexpr const char* kMeasure = R"(<script>
window.addEventListener('load', () => {
  const lines = [];
  document.querySelectorAll('figure svg').forEach(svg => {
    const box = svg.getBoundingClientRect();
    let elements = 0, inked = 0;
    svg.querySelectorAll('path, polyline, polygon, line, text').forEach(e => {
      ++elements;
      const b = e.getBBox();
      if (b.width > 0 || b.height > 0) ++inked;
    });
    lines.push([Math.round(box.width), Math.round(box.height), elements, inked].join(' '));
  });
  const pre = document.createElement('pre');
  pre.id = 'foglab-measure';
  pre.textContent = lines.join('\n');
  // The sections asked for (window.foglabSections): "selector height", 0 when absent.
  const sections = (window.foglabSections || []).map(sel => {
    const e = document.querySelector(sel);
    return sel + ' ' + (e ? Math.round(e.getBoundingClientRect().height) : 0);
  });
  const spre = document.createElement('pre');
  spre.id = 'foglab-sections';
  spre.textContent = sections.join('\n');
  document.body.appendChild(pre);
  document.body.appendChild(spre);
});
</script>
)";

/// Runs headless Chromium with the issue's flags (plus a private profile
/// directory) on `page`; `what` is --dump-dom or --screenshot=FILE.
std::string chromium(const fs::path& profile, const std::string& what, const fs::path& page,
                     const fs::path& output) {
  const std::string command =
      "timeout 180 chromium --headless --no-sandbox --disable-gpu "
      "--disable-background-networking --no-first-run --user-data-dir='" +
      profile.string() + "' --window-size=1100,4000 " + what + " 'file://" + page.string() +
      "' > '" + output.string() + "' 2>/dev/null";
  const int status = std::system(command.c_str());
  EXPECT_EQ(status, 0) << command;
  return test::read_file(output);
}

/// The lab-2 page's parts beside its plots (issue 23).
const std::vector<std::string> kLab2Sections = {".title-block", "#comparison",
                                                "#temperature-question", "#conclusions"};

bool have_chromium() { return std::system("command -v chromium > /dev/null 2>&1") == 0; }

/// Opens `report` (a copy with the measuring script) in Chromium and
/// checks every figure's SVG as laid out, and that each of `sections` (CSS
/// selectors) is laid out with a height; returns how many figures there were.
int expect_rendered_figures(const fs::path& report, const fs::path& dir,
                            const std::vector<std::string>& sections = {}) {
  std::string page = test::read_file(report);
  const std::size_t body_end = page.rfind("</body>");
  EXPECT_NE(body_end, std::string::npos);
  if (body_end == std::string::npos) return 0;
  std::string selectors = "<script>window.foglabSections = [";
  for (const std::string& s : sections) selectors += "'" + s + "',";
  page.insert(body_end, selectors + "];</script>\n" + kMeasure);
  const fs::path measured = dir / "measured.html";
  std::ofstream(measured) << page;

  const std::string dom = chromium(dir / "profile", "--dump-dom", measured, dir / "dom.html");
  const std::string open = "<pre id=\"foglab-measure\">";
  const std::size_t start = dom.find(open);
  EXPECT_NE(start, std::string::npos) << "the measuring script did not run:\n"
                                      << dom.substr(0, 500);
  if (start == std::string::npos) return 0;
  const std::string sections_open = "<pre id=\"foglab-sections\">";
  const std::size_t sections_at = dom.find(sections_open);
  EXPECT_NE(sections_at, std::string::npos);
  if (sections_at != std::string::npos) {
    std::istringstream laid(
        dom.substr(sections_at + sections_open.size(),
                   dom.find("</pre>", sections_at) - sections_at - sections_open.size()));
    std::size_t seen = 0;
    for (std::string selector; laid >> selector;) {
      int height = 0;
      laid >> height;
      ++seen;
      EXPECT_GT(height, 10) << selector << " is not laid out";
    }
    EXPECT_EQ(seen, sections.size());
  }
  const std::size_t end = dom.find("</pre>", start);
  std::istringstream lines(dom.substr(start + open.size(), end - start - open.size()));
  int figures = 0;
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line);
    int width = 0, height = 0, elements = 0, inked = 0;
    EXPECT_TRUE(fields >> width >> height >> elements >> inked) << line;
    ++figures;
    // The report's SVGs are 720x480, scaled to the 1000-px column at most.
    EXPECT_GE(width, 400) << "figure " << figures;
    EXPECT_GE(height, 250) << "figure " << figures;
    // Axes, tick labels, curves and the legend: dozens of drawn elements.
    EXPECT_GE(inked, 20) << "figure " << figures << ": " << line;
    EXPECT_GE(inked, elements / 3) << "figure " << figures << ": " << line;
  }
  return figures;
}

/// A screenshot of `report` carries far more ink than one of a blank page.
void expect_not_blank_as_rendered(const fs::path& report, const fs::path& dir) {
  // A screenshot of the report against one of an empty page: a blank
  // 1100x4000 window is ~21 kB of PNG, a page of text and tables 400 kB or
  // more (the plots themselves are checked by the measurements above).
  const fs::path blank = dir / "blank.html";
  std::ofstream(blank) << "<!DOCTYPE html><html><body></body></html>\n";
  chromium(dir / "profile", "--screenshot='" + (dir / "blank.png").string() + "'", blank,
           dir / "log1.txt");
  chromium(dir / "profile", "--screenshot='" + (dir / "report.png").string() + "'", report,
           dir / "log2.txt");
  EXPECT_TRUE(fs::exists(dir / "blank.png"));
  EXPECT_TRUE(fs::exists(dir / "report.png"));
  if (fs::exists(dir / "blank.png") && fs::exists(dir / "report.png")) {
    EXPECT_GT(fs::file_size(dir / "report.png"), 5 * fs::file_size(dir / "blank.png"))
        << fs::file_size(dir / "report.png") << " bytes against "
        << fs::file_size(dir / "blank.png");
  }
}

TEST(BrowserTest, Lab2ReportPlotsRenderInChromium) {
  ASSERT_TRUE(have_chromium())
      << "chromium is not installed: run 'bash scripts/install-deps.sh --tests'";
  test::TempDir dir;
  const test::CliRun r = test::run_foglab("lab2 --student 'Ivanov I.' --group R3241 --out " +
                                          test::quote(dir / "report"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Two gyros x two runs x four plots, and the report's required parts (issue 23): the title
  // page, FOG1 against FOG2, review question 18 answered, the conclusions.
  EXPECT_EQ(expect_rendered_figures(dir / "report" / "report.html", dir.path(), kLab2Sections), 16);
  expect_not_blank_as_rendered(dir / "report" / "report.html", dir.path());
  const std::string page = test::read_file(dir / "report" / "report.html");
  for (const char* heading : {"<h2>Aim of the work</h2>", "<h2>FOG1 against FOG2</h2>",
                              "<h3>Review question 18", "<h2>Conclusions</h2>", "Ivanov I."}) {
    EXPECT_NE(page.find(heading), std::string::npos) << heading;
  }
}

TEST(BrowserTest, RussianLab2ReportPlotsRenderInChromium) {
  // `lab2 --lang ru` (issue 20): Cyrillic titles, axes and legends lay out as the English.
  ASSERT_TRUE(have_chromium())
      << "chromium is not installed: run 'bash scripts/install-deps.sh --tests'";
  test::TempDir dir;
  const test::CliRun r = test::run_foglab(
      "lab2 --lang ru --student 'Иванов И.' --group R3241 --out " + test::quote(dir / "report"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(expect_rendered_figures(dir / "report" / "report.html", dir.path(), kLab2Sections), 16);
  const std::string page = test::read_file(dir / "report" / "report.html");
  for (const char* heading : {"<h2>Цель работы</h2>", "<h2>Сравнение FOG1 и FOG2</h2>",
                              "<h3>Контрольный вопрос 18", "<h2>Выводы</h2>", "Иванов И."}) {
    EXPECT_NE(page.find(heading), std::string::npos) << heading;
  }
}

TEST(BrowserTest, Lab1ReportPlotsRenderInChromium) {
  ASSERT_TRUE(have_chromium())
      << "chromium is not installed: run 'bash scripts/install-deps.sh --tests'";
  test::TempDir dir;
  const test::CliRun r = test::run_foglab("lab1 --out " + test::quote(dir / "report"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(expect_rendered_figures(dir / "report" / "report.html", dir.path()), 11);
}

TEST(BrowserTest, RussianLab1ReportRendersInChromium) {
  // `lab1 --lang ru` (issue 20): Cyrillic titles, axis labels and legends in all eleven SVGs.
  ASSERT_TRUE(have_chromium())
      << "chromium is not installed: run 'bash scripts/install-deps.sh --tests'";
  test::TempDir dir;
  const test::CliRun r =
      test::run_foglab("lab1 --lang ru --student 'Петров П.' --out " + test::quote(dir / "report"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string page = test::read_file(dir / "report" / "report.html");
  EXPECT_NE(page.find("<html lang=\"ru\">"), std::string::npos);
  EXPECT_NE(page.find(">действующая угловая скорость [°/с]<"), std::string::npos);
  for (const char* part : {"<h2>Цель работы</h2>", "<h2>Выводы</h2>", "Петров П."}) {
    EXPECT_NE(page.find(part), std::string::npos) << part;
  }
  EXPECT_EQ(expect_rendered_figures(dir / "report" / "report.html", dir.path(), {".title-block"}),
            11);
}

TEST(BrowserTest, RussianCalibrationReportRendersInChromium) {
  // `calibrate --lang ru` (issue 20): the Russian page lays out its four plots (Cyrillic
  // titles and axis labels in the SVGs) as the English one does.
  ASSERT_TRUE(have_chromium())
      << "chromium is not installed: run 'bash scripts/install-deps.sh --tests'";
  test::TempDir dir;
  const std::string run = test::quote(dir / "run.csv");
  ASSERT_EQ(test::run_foglab("rate-table --out " + run + " --temps 0,40 --plateau 20").exit_code,
            0);
  const test::CliRun r =
      test::run_foglab("calibrate " + run + " --lang ru --report " + test::quote(dir / "ru.html"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(expect_rendered_figures(dir / "ru.html", dir.path()), 4);
}

TEST(BrowserTest, RussianAnalyzeReportRendersInChromium) {
  // `analyze --report --lang ru` (issue 20): the record, bias-temperature, PSD and Allan
  // deviation plots of a generated recording with a temperature ramp, with Cyrillic titles,
  // axis labels and legends, laid out as the English ones are.
  ASSERT_TRUE(have_chromium())
      << "chromium is not installed: run 'bash scripts/install-deps.sh --tests'";
  test::TempDir dir;
  const std::string recording = test::quote(dir / "fog.mat");
  ASSERT_EQ(test::run_foglab("generate --N 0.5 --B 0.05 --K 0.005 --Q 0.5 --temp-coef 0.8 "
                             "--temperature ramp:10 --fs 10 --hours 1 --out " +
                             recording)
                .exit_code,
            0);
  const test::CliRun r = test::run_foglab("analyze " + recording + " --lang ru --report " +
                                          test::quote(dir / "ru.html"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(expect_rendered_figures(dir / "ru.html", dir.path()), 4);
  expect_not_blank_as_rendered(dir / "ru.html", dir.path());
}

}  // namespace
}  // namespace foglab
