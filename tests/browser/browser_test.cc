// The lab-2 report opened in a real browser (issue 5): headless Chromium
// loads the page `foglab lab2` writes, and a script added to a copy of it
// measures every figure's SVG as laid out — its size on the page and how
// many of its drawn elements (lines, text) have a non-empty box. A page
// whose SVG did not parse, or whose plots are empty, fails. A screenshot of
// the page must also carry far more ink (PNG bytes) than one of a blank page.
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
  document.body.appendChild(pre);
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

bool have_chromium() { return std::system("command -v chromium > /dev/null 2>&1") == 0; }

TEST(BrowserTest, Lab2ReportPlotsRenderInChromium) {
  ASSERT_TRUE(have_chromium())
      << "chromium is not installed: run 'bash scripts/install-deps.sh --tests'";
  test::TempDir dir;
  const test::CliRun r = test::run_foglab("lab2 --out " + test::quote(dir / "report"));
  ASSERT_EQ(r.exit_code, 0) << r.err;

  std::string page = test::read_file(dir / "report" / "report.html");
  const std::size_t body_end = page.rfind("</body>");
  ASSERT_NE(body_end, std::string::npos);
  page.insert(body_end, kMeasure);
  const fs::path measured = dir / "measured.html";
  std::ofstream(measured) << page;

  const std::string dom = chromium(dir / "profile", "--dump-dom", measured, dir / "dom.html");
  const std::string open = "<pre id=\"foglab-measure\">";
  const std::size_t start = dom.find(open);
  ASSERT_NE(start, std::string::npos) << "the measuring script did not run:\n"
                                      << dom.substr(0, 500);
  const std::size_t end = dom.find("</pre>", start);
  std::istringstream lines(dom.substr(start + open.size(), end - start - open.size()));
  int figures = 0;
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line);
    int width = 0, height = 0, elements = 0, inked = 0;
    ASSERT_TRUE(fields >> width >> height >> elements >> inked) << line;
    ++figures;
    // The report's SVGs are 720x480 at most, scaled to the 1000-px column.
    EXPECT_GE(width, 400) << "figure " << figures;
    EXPECT_GE(height, 250) << "figure " << figures;
    // Axes, tick labels, curves and the legend: dozens of drawn elements.
    EXPECT_GE(inked, 20) << "figure " << figures << ": " << line;
    EXPECT_GE(inked, elements / 3) << "figure " << figures << ": " << line;
  }
  // Two gyros x two runs x four plots.
  EXPECT_EQ(figures, 16);

  // A screenshot of the report against one of an empty page.
  const fs::path blank = dir / "blank.html";
  std::ofstream(blank) << "<!DOCTYPE html><html><body></body></html>\n";
  chromium(dir / "profile", "--screenshot='" + (dir / "blank.png").string() + "'", blank,
           dir / "log1.txt");
  chromium(dir / "profile", "--screenshot='" + (dir / "report.png").string() + "'",
           dir / "report" / "report.html", dir / "log2.txt");
  ASSERT_TRUE(fs::exists(dir / "blank.png"));
  ASSERT_TRUE(fs::exists(dir / "report.png"));
  EXPECT_GT(fs::file_size(dir / "report.png"), 20 * fs::file_size(dir / "blank.png"))
      << fs::file_size(dir / "report.png") << " bytes against " << fs::file_size(dir / "blank.png");
}

}  // namespace
}  // namespace foglab
