// The report of one analysis: plots, self-contained HTML, Markdown, Kalibr.
#include "foglab/report/report.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/core/output.h"
#include "foglab/core/units.h"
#include "foglab/model/analysis.h"
#include "foglab/report/imu.h"
#include "foglab/report/plot.h"
#include "foglab/sim/generator.h"
#include "foglab/sim/sensor_output.h"
#include "support/files.h"

namespace foglab::report {
namespace {

/// A two-hour 10 Hz recording under a 10 degC ramp: white noise, flicker,
/// a small random walk and a linear temperature sensitivity, analysed once.
struct Analysed {
  model::AnalysisResult result;
  ReportInput input;
};

const Analysed& analysed() {
  static const Analysed a = [] {
    sim::ErrorModel m;
    m.noise.N = 0.5;
    m.noise.B = 0.05;
    m.noise.K = 0.005;
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
    Analysed out;
    out.input.file_name = "sim <ramp> & co.mat";
    out.input.channel = "Y2";
    out.input.temperature_channel = "T2";
    out.input.preview = preview_record(rec.rate_deg_h, rec.temperature_c, rec.sample_rate_hz);
    out.input.notes = {Message::verbatim("a caller's note")};
    out.result = model::analyze(rec.rate_deg_h, rec.temperature_c, rec.sample_rate_hz);
    return out;
  }();
  return a;
}

/// The number after "key:" on the YAML line that starts with it.
double yaml_number(const std::string& yaml, const std::string& key) {
  const std::regex re("(^|\n)" + key + ":\\s*([-+0-9.eE]+)");
  std::smatch m;
  if (!std::regex_search(yaml, m, re)) return std::nan("");
  return std::stod(m[2].str());
}

TEST(Kalibr, ConversionsMatchHandComputedNumbers) {
  // 0.5 deg/h/sqrt(Hz) = 0.5 * (pi/180) rad / 3600 s / sqrt(Hz).
  EXPECT_NEAR(noise_density_rad_s_sqrt_hz(0.5), 2.42406840554768e-06, 1e-18);
  // 0.02 deg/h/sqrt(s) = 0.02 * (pi/180) / 3600 rad/s/sqrt(s), and
  // 1/sqrt(s) = sqrt(Hz) / s: rad/s^2/sqrt(Hz).
  EXPECT_NEAR(random_walk_rad_s2_sqrt_hz(0.02), 9.69627362219072e-08, 1e-20);
  EXPECT_NEAR(noise_density_rad_s_sqrt_hz(1.0), 4.84813681109536e-06, 1e-18);
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(Kalibr, AnUnresolvedRandomWalkIsBoundedByTheAllanDeviation) {
  // A fit that took the long taus with another term and left K with a loose
  // bound: the Allan deviation's upper limits bound it, K sqrt(tau/3) <=
  // ci95_high(tau) at every tau, so the value for a filter is the smallest
  // ci95_high / sqrt(tau/3), here 2e-4 / sqrt(300/3) = 2e-5.
  model::AnalysisResult r;
  r.sample_rate_hz = 100.0;
  r.noise.N = {0.002, 0.0019, 0.0021, kNaN, model::TermStatus::resolved};
  r.noise.K = {0.9, 0.0, 0.9, 0.9, model::TermStatus::upper_bound};
  r.allan.tau_s = {3.0, 30.0, 300.0};
  r.allan.ci95_high = {2e-3, 6e-4, 2e-4};
  const FilterNoise f = filter_noise(r, Sensor::accelerometer);
  EXPECT_FALSE(f.random_walk_resolved);
  EXPECT_NEAR(f.random_walk, 2e-5, 1e-12);
  EXPECT_NE(f.random_walk_source.find("tau = 300 s"), std::string::npos) << f.random_walk_source;
  EXPECT_NE(f.random_walk_source.find("m/s^2/sqrt(s)"), std::string::npos);
  // A fit's bound tighter than the Allan deviation's stays.
  r.noise.K = {1e-5, 0.0, 1e-5, 1e-5, model::TermStatus::upper_bound};
  EXPECT_NEAR(filter_noise(r, Sensor::accelerometer).random_walk, 1e-5, 1e-15);
  // Resolved: the fit's value and interval, in Kalibr's units for a gyroscope.
  r.noise.K = {2.0, 1.0, 3.0, kNaN, model::TermStatus::resolved};
  const FilterNoise g = filter_noise(r, Sensor::gyroscope);
  EXPECT_TRUE(g.random_walk_resolved);
  EXPECT_DOUBLE_EQ(g.random_walk, 2.0);
  EXPECT_NEAR(g.random_walk * kalibr_factor(Sensor::gyroscope), random_walk_rad_s2_sqrt_hz(2.0),
              1e-20);
}

TEST(Kalibr, ImuYamlCarriesTheConvertedFit) {
  const Analysed& a = analysed();
  const model::NoiseFitResult& n = a.result.noise;
  const std::string yaml = kalibr_imu_yaml(a.result, a.input, "/fog");
  ASSERT_EQ(n.N.status, model::TermStatus::resolved);
  EXPECT_NEAR(yaml_number(yaml, "gyroscope_noise_density"),
              n.N.value * std::numbers::pi / 180.0 / 3600.0,
              1e-8 * n.N.value * std::numbers::pi / 180.0 / 3600.0);
  // An unresolved K: the fit's bound, or the Allan deviation's when tighter
  // (report/imu.h filter_noise()).
  double adev_bound = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < a.result.allan.tau_s.size(); ++k) {
    adev_bound = std::min(adev_bound,
                          a.result.allan.ci95_high[k] / std::sqrt(a.result.allan.tau_s[k] / 3.0));
  }
  const double k =
      n.K.status == model::TermStatus::resolved ? n.K.value : std::min(n.K.upper_95, adev_bound);
  ASSERT_TRUE(std::isfinite(k) && k > 0.0) << yaml;
  EXPECT_NEAR(yaml_number(yaml, "gyroscope_random_walk"), k * std::numbers::pi / 180.0 / 3600.0,
              1e-8 * k * std::numbers::pi / 180.0 / 3600.0);
  if (n.K.status != model::TermStatus::resolved) {
    EXPECT_NE(yaml.find("upper bound"), std::string::npos) << yaml;
  }
  EXPECT_DOUBLE_EQ(yaml_number(yaml, "update_rate"), 10.0);
  EXPECT_NE(yaml.find("\nrostopic: /fog"), std::string::npos) << yaml;
  // No accelerometer: its fields only in comments.
  EXPECT_TRUE(std::isnan(yaml_number(yaml, "accelerometer_noise_density"))) << yaml;
  EXPECT_TRUE(std::isnan(yaml_number(yaml, "accelerometer_random_walk"))) << yaml;
  EXPECT_NE(yaml.find("#accelerometer_noise_density"), std::string::npos);
}

TEST(Report, HtmlHasFourInlinePlotsAndNoNetworkReferences) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const Analysed& a = analysed();
  const Report rep = make_report(a.result, a.input);
  ASSERT_FALSE(rep.plots_skipped) << rep.plots_note;
  ASSERT_EQ(rep.figures.size(), 4u);
  for (const Figure& f : rep.figures) EXPECT_TRUE(f.svg.has_value()) << f.name << ": " << f.error;
  const std::string html = html_document(rep);
  EXPECT_EQ(test::occurrences(html, "<svg"), 4u);
  EXPECT_EQ(test::occurrences(html, "</svg>"), 4u);
  EXPECT_EQ(html.find("<?xml"), std::string::npos);
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  // The only URLs are the XML namespace names of SVG (never fetched).
  std::string stripped = html;
  for (const std::string ns :
       {"xmlns=\"http://www.w3.org/2000/svg\"", "xmlns:xlink=\"http://www.w3.org/1999/xlink\""}) {
    for (std::size_t p = stripped.find(ns); p != std::string::npos; p = stripped.find(ns)) {
      stripped.erase(p, ns.size());
    }
  }
  EXPECT_EQ(stripped.find("http://"), std::string::npos);
  EXPECT_EQ(stripped.find("https://"), std::string::npos);
  EXPECT_EQ(stripped.find("src="), std::string::npos);
  EXPECT_EQ(stripped.find("<link"), std::string::npos);
  // gnuplot names its elements alike in every plot: inlined, they are made distinct.
  const std::regex id_re("\\sid=['\"]([^'\"]+)['\"]");
  std::multiset<std::string> ids;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), id_re);
       it != std::sregex_iterator(); ++it) {
    ids.insert((*it)[1].str());
  }
  ASSERT_FALSE(ids.empty());
  for (const std::string& id : ids) EXPECT_EQ(ids.count(id), 1u) << id;
  // Axis labels with units, the plots' legends.
  for (const std::string label :
       {"time [h]", "rate [deg/h]", "temperature [degC]", "tau [s]", "Allan deviation [deg/h]",
        "frequency [Hz]", "sqrt(PSD) [deg/h/sqrt(Hz)]", "95 % interval", "fit N+",
        "white noise N (-1/2)", "OADEV"}) {
    EXPECT_NE(html.find(label), std::string::npos) << label;
  }
  // Written atomically through the shared writer.
  test::TempDir dir;
  write_text_file(dir.file("report.html"), html);
  EXPECT_EQ(test::read_file(dir / "report.html"), html);
}

TEST(Report, HtmlNamesEveryParameterWithItsUnit) {
  const Analysed& a = analysed();
  ReportOptions o;
  o.plots = false;
  const Report rep = make_report(a.result, a.input, o);
  const std::string html = html_document(rep);
  for (const NoiseParameter& p : kNoiseParameters) {
    EXPECT_NE(html.find("<td>" + std::string(p.name) + "</td>"), std::string::npos) << p.name;
    EXPECT_NE(html.find("<td>" + std::string(p.unit) + "</td>"), std::string::npos) << p.unit;
    EXPECT_NE(rep.markdown.find("| " + std::string(p.name) + " |"), std::string::npos) << p.name;
  }
  for (const std::string text :
       {"resolved", "95 % interval", "deg/sqrt(h)", "Accuracy class", "Random bias",
        "graphical readings", "lab&#39;s polyfit(T, Y, 2) constant term", "a caller&#39;s note",
        "sim &lt;ramp&gt; &amp; co.mat", "deg/h/degC"}) {
    EXPECT_NE(html.find(text), std::string::npos) << text;
  }
  EXPECT_EQ(html.find("sim <ramp>"), std::string::npos);
  // The fit's status, in both.
  const std::string fit = "Fit: " + a.result.noise.message + ".";
  EXPECT_NE(html.find("<p class=\"fit-converged\">" + html_escape(fit) + "</p>"),
            std::string::npos);
  EXPECT_NE(rep.markdown.find(fit), std::string::npos);
  EXPECT_NE(html.find(std::string(to_string(a.result.verdict.accuracy_class))), std::string::npos);
  EXPECT_NE(rep.markdown.find("plots were skipped"), std::string::npos);
  EXPECT_NE(html.find("plotting was turned off"), std::string::npos);
}

/// The page's text with html_escape() undone (its five entities).
std::string html_unescape(std::string text) {
  for (const auto& [entity, c] :
       {std::pair{"&lt;", "<"}, std::pair{"&gt;", ">"}, std::pair{"&quot;", "\""},
        std::pair{"&#39;", "'"}, std::pair{"&amp;", "&"}}) {
    const std::string e = entity;
    for (std::size_t at = text.find(e); at != std::string::npos; at = text.find(e, at + 1)) {
      text.replace(at, e.size(), c);
    }
  }
  return text;
}

TEST(Report, TheManualsReadingsOfKAndQStandBesideFoglabs) {
  // Issue 23: where the manual's text reads differently (K on the +1/2 line at tau = 1 s, its
  // PSD line at 1 Hz; C = sqrt(3) Q), the report says so with the number the text would give.
  sim::ErrorModel m;
  m.noise.N = 0.5;
  m.noise.K = 0.05;
  m.noise.Q = 0.5;
  sim::GeneratorOptions g;
  g.sample_rate_hz = 10.0;
  g.duration_s = 7200.0;
  g.seed = 12;
  sim::Recording rec = sim::generate(m, sim::TemperatureProfile{}, g);
  const model::AnalysisResult r =
      model::analyze(rec.rate_deg_h, rec.temperature_c, rec.sample_rate_hz);
  ASSERT_TRUE(r.adev_readings.K.has_value());
  ASSERT_TRUE(r.psd_readings.K.has_value());
  ASSERT_EQ(r.noise.Q.status, model::TermStatus::resolved);
  ReportOptions o;
  o.plots = false;
  ReportInput in;
  in.file_name = "kq.mat";
  const Report rep = make_report(r, in, o);
  const std::string k = fmt::format(
      "K/sqrt(3) = {:.4g}, the -2 line's level at 1 Hz K/(2 pi) = {:.4g} deg/h/sqrt(s)",
      *r.adev_readings.K / std::sqrt(3.0), *r.psd_readings.K / (2.0 * std::numbers::pi));
  const std::string q =
      fmt::format("C = sqrt(3) Q = {:.4g} deg/h*s", std::sqrt(3.0) * r.noise.Q.value);
  for (const std::string& page : {html_unescape(rep.html_section), rep.markdown}) {
    EXPECT_NE(page.find(k), std::string::npos) << k;
    EXPECT_NE(page.find(q), std::string::npos) << q;
    EXPECT_NE(page.find("docs/manual_notes.md"), std::string::npos);
  }
  // The readings the manual's way are what the lines give there: K/sqrt(3) is within the
  // truth's factor of the true K/sqrt(3) as the reading is of K.
  EXPECT_NEAR(*r.adev_readings.K / m.noise.K, 1.0, 0.5);

  // White noise alone: a line only for what the record shows.
  sim::ErrorModel white;
  white.noise.N = 0.5;
  sim::Recording w = sim::generate(white, sim::TemperatureProfile{}, g);
  const model::AnalysisResult rw = model::analyze(w.rate_deg_h, w.temperature_c, w.sample_rate_hz);
  const Report plain = make_report(rw, in, o);
  EXPECT_EQ(plain.html_section.find("K/sqrt(3)") != std::string::npos,
            rw.adev_readings.K || rw.psd_readings.K);
  EXPECT_EQ(plain.html_section.find("C = sqrt(3) Q") != std::string::npos,
            rw.noise.Q.status == model::TermStatus::resolved);
}

TEST(Report, MissingGnuplotStillGivesTheReport) {
  const Analysed& a = analysed();
  ReportOptions o;
  o.plot.gnuplot = "/nonexistent/gnuplot";
  const Report rep = make_report(a.result, a.input, o);
  EXPECT_TRUE(rep.plots_skipped);
  const std::string html = html_document(rep);
  EXPECT_NE(html.find("The plots were skipped: gnuplot could not be run"), std::string::npos)
      << rep.plots_note;
  EXPECT_NE(html.find("/nonexistent/gnuplot"), std::string::npos);
  EXPECT_EQ(html.find("<svg"), std::string::npos);
  EXPECT_NE(html.find("<td>gm_tc</td>"), std::string::npos);
  EXPECT_NE(rep.markdown.find("plots were skipped"), std::string::npos);
  EXPECT_FALSE(rep.kalibr_yaml.empty());
  EXPECT_FALSE(render_svg(Plot{}, o.plot).svg.has_value());
  EXPECT_TRUE(render_svg(Plot{}, o.plot).gnuplot_missing);
  EXPECT_FALSE(gnuplot_available("/nonexistent/gnuplot"));
}

TEST(Report, WithoutTemperatureThereIsNoBiasPlot) {
  const Analysed& a = analysed();
  ReportInput in = a.input;
  in.preview.temperature_c.clear();
  in.temperature_channel.clear();
  model::AnalysisResult r = a.result;
  r.systematic.reset();
  const std::vector<Plot> plots = report_plots(r, in);
  ASSERT_EQ(plots.size(), 3u);
  EXPECT_EQ(plots[0].x_label, "time [h]");
  EXPECT_EQ(plots[1].x_label, "frequency [Hz]");
  EXPECT_EQ(plots[2].x_label, "tau [s]");
  ReportOptions o;
  o.plots = false;
  const Report rep = make_report(r, in, o);
  ASSERT_EQ(rep.figures.size(), 3u);
  EXPECT_EQ(rep.figures[1].name, "psd");
  EXPECT_EQ(rep.figures[2].name, "adev");
}

// One hour at 100 Hz of `m` (white noise N = 150 deg/h/sqrt(Hz) and the
// sensor-output effects the caller sets), from generator seed `seed`.
sim::Recording effects_hour(sim::ErrorModel m, std::uint64_t seed) {
  m.noise.N = 150.0;
  sim::GeneratorOptions g;
  g.sample_rate_hz = 100.0;
  g.duration_s = 3600.0;
  g.seed = seed;
  return sim::generate(m, sim::TemperatureProfile{}, g);
}

// The first series of `plot` whose title starts with `start`, or null.
const Series* titled(const Plot& plot, const std::string& start) {
  for (const Series& s : plot.series) {
    if (s.title.rfind(start, 0) == 0) return &s;
  }
  return nullptr;
}

TEST(Report, PlotsMarkStepsSpikesAndTheBandwidth) {
  // A filtered record with a step and two spikes: the time plot draws the
  // step at its time and a mark at each spike, the Allan plot shades where
  // the filter lowers the white level by more than 1 %.
  sim::ErrorModel m;
  m.output.filter_time_constant_s = 0.01;
  m.output.steps = {{1000.0, 2000.0}};
  sim::Recording rec = effects_hour(m, 2);
  rec.rate_deg_h[50000] += 60000.0;
  rec.rate_deg_h[200000] -= 60000.0;
  ReportInput in;
  in.file_name = "effects.mat";
  in.preview = preview_record(rec.rate_deg_h, {}, rec.sample_rate_hz);
  const model::AnalysisResult r = model::analyze(rec.rate_deg_h, {}, rec.sample_rate_hz);
  ASSERT_EQ(r.steps.indices.size(), 1u);
  ASSERT_EQ(r.spikes.count, 2);
  ASSERT_TRUE(r.noise.bandwidth.resolved);
  const std::vector<Plot> plots = report_plots(r, in);
  ASSERT_EQ(plots.size(), 3u);
  const Series* step = titled(plots[0], "bias step");
  ASSERT_NE(step, nullptr);
  EXPECT_NEAR(step->x.front(), 1000.0 / 3600.0, 1.0 / 3600.0);
  const Series* spikes = titled(plots[0], "spike");
  ASSERT_NE(spikes, nullptr);
  ASSERT_EQ(spikes->x.size(), 2u);
  EXPECT_NEAR(spikes->x[0], 500.0 / 3600.0, 1e-9);
  EXPECT_NEAR(spikes->x[1], 2000.0 / 3600.0, 1e-9);
  const Series* region = titled(plots[2], "sensor bandwidth");
  ASSERT_NE(region, nullptr);
  EXPECT_DOUBLE_EQ(region->x.front(), r.allan.tau_s.front());
  // The filter's effect at the region's end is 1 % (to the 5 % grid step).
  const double end = region->x.back();
  const double lowered = 1.0 - white_allan_factor(r.noise.bandwidth.bandwidth, end,
                                                  r.noise.bandwidth.sample_interval_s);
  EXPECT_LE(lowered, 0.01);
  EXPECT_GT(lowered, 0.01 / 1.1);
}

TEST(Report, PsdPlotShadesTheSpectralLine) {
  // A 20 Hz sinusoid of 1,000 deg/h amplitude on the white noise: the PSD
  // plot shades the line's bins, around 20 Hz and narrower than 1 Hz, and
  // names its rms; a record without one has no such region.
  sim::ErrorModel m;
  m.output.sinusoids = {{20.0, 1000.0, 0.0}};
  sim::Recording rec = effects_hour(m, 4);
  ReportInput in;
  in.preview = preview_record(rec.rate_deg_h, {}, rec.sample_rate_hz);
  const model::AnalysisResult r = model::analyze(rec.rate_deg_h, {}, rec.sample_rate_hz);
  ASSERT_EQ(r.noise.lines.size(), 1u);
  const std::vector<Plot> plots = report_plots(r, in);
  const Series* region = titled(plots[1], "spectral line 20");
  ASSERT_NE(region, nullptr);
  EXPECT_EQ(region->style, SeriesStyle::band);
  EXPECT_FALSE(region->sets_range);
  ASSERT_EQ(region->x.size(), 2u);
  EXPECT_LT(region->x[0], 20.0);
  EXPECT_GT(region->x[1], 20.0);
  EXPECT_LT(region->x[1] - region->x[0], 1.0);
  EXPECT_NE(region->title.find(" deg/h rms"), std::string::npos) << region->title;
  EXPECT_NEAR(std::sqrt(r.noise.lines.front().variance), 1000.0 / std::sqrt(2.0), 50.0);

  sim::Recording plain = effects_hour(sim::ErrorModel{}, 4);
  const model::AnalysisResult none = model::analyze(plain.rate_deg_h, {}, plain.sample_rate_hz);
  ASSERT_TRUE(none.noise.lines.empty());
  EXPECT_EQ(titled(report_plots(none, in)[1], "spectral line"), nullptr);
}

TEST(Report, ADriftingWhiteLevelGetsItsOwnPlotOverTheRun) {
  // White noise whose variance rises by 30 % over the hour: the short taus
  // are called drifting, and a fifth plot shows each tau's blocks against
  // time as a change from their mean, the called taus in colour; a
  // stationary record has no such plot.
  sim::Recording rec = effects_hour(sim::ErrorModel{}, 5);
  const double n = static_cast<double>(rec.rate_deg_h.size());
  for (std::size_t i = 0; i < rec.rate_deg_h.size(); ++i) {
    rec.rate_deg_h[i] *= std::sqrt(1.0 + 0.3 * static_cast<double>(i) / n);
  }
  ReportInput in;
  in.preview = preview_record(rec.rate_deg_h, {}, rec.sample_rate_hz);
  const model::AnalysisResult r = model::analyze(rec.rate_deg_h, {}, rec.sample_rate_hz);
  const stats::AllanDrift& d = r.allan_drift;
  ASSERT_TRUE(d.any());
  ASSERT_TRUE(d.drifting[0]);
  const std::vector<Plot> plots = report_plots(r, in);
  ASSERT_EQ(plots.size(), 4u);  // time, PSD, Allan deviation, drift
  const Plot& drift = plots[3];
  EXPECT_EQ(drift.x_label, "time [h]");
  EXPECT_NE(drift.y_label.find("[%]"), std::string::npos);
  ASSERT_EQ(drift.series.size(), d.tau_s.size());
  const Series& first = drift.series[0];
  EXPECT_EQ(first.title.rfind("tau 0.01 s: z +", 0), 0u) << first.title;
  EXPECT_EQ(first.style, SeriesStyle::linespoints);
  ASSERT_EQ(first.x.size(), 32u);
  EXPECT_NEAR(first.x.front(), 0.5 / 32.0, 1e-3);  // hours: the first block's middle
  EXPECT_NEAR(first.x.back(), 31.5 / 32.0, 1e-3);
  // Against the truth: the variance at a block's middle over the mean
  // variance (1.15), as an Allan deviation's change in %; at one sample a
  // block's Allan deviation (11,250 samples) scatters by about 0.8 %
  // (4 sd allowed).
  for (std::size_t b = 0; b < 32; ++b) {
    const double truth = 100.0 * (std::sqrt((1.0 + 0.3 * (b + 0.5) / 32.0) / 1.15) - 1.0);
    EXPECT_NEAR(first.y[b], truth, 3.5) << "block " << b;
  }
  // The taus not called, if any, are plain lines with one legend entry.
  int steady = 0, steady_titles = 0;
  for (std::size_t i = 0; i < d.tau_s.size(); ++i) {
    if (d.drifting[i]) continue;
    EXPECT_EQ(drift.series[i].style, SeriesStyle::lines);
    ++steady;
    steady_titles += !drift.series[i].title.empty();
  }
  EXPECT_EQ(steady_titles, steady > 0 ? 1 : 0);
  ReportOptions o;
  o.plots = false;
  const Report rep = make_report(r, in, o);
  ASSERT_EQ(rep.figures.size(), 4u);
  EXPECT_EQ(rep.figures[3].name, "allan_drift");
  EXPECT_NE(rep.figures[3].caption.find("32 blocks"), std::string::npos);
  // The summary says which taus trend, and says the check passed where it did.
  EXPECT_NE(rep.markdown.find("short-tau stationarity: the Allan variance trends over the run at "
                              "tau 0.01"),
            std::string::npos)
      << rep.markdown;

  sim::Recording plain = effects_hour(sim::ErrorModel{}, 5);
  const model::AnalysisResult stationary =
      model::analyze(plain.rate_deg_h, {}, plain.sample_rate_hz);
  EXPECT_FALSE(stationary.allan_drift.any());
  EXPECT_EQ(report_plots(stationary, in).size(), 3u);
  EXPECT_NE(
      make_report(stationary, in, o)
          .markdown.find("short-tau stationarity: no trend over the run at tau 0.01 to 0.32 s "
                         "(32 blocks"),
      std::string::npos);
  // Under 32 blocks of 256 samples: not checked, and said so.
  plain.rate_deg_h.resize(8000);
  const model::AnalysisResult short_record =
      model::analyze(plain.rate_deg_h, {}, plain.sample_rate_hz);
  EXPECT_EQ(short_record.allan_drift.blocks, 0);
  EXPECT_NE(make_report(short_record, in, o).markdown.find("short-tau stationarity: not checked"),
            std::string::npos);
}

// An hour (seed 3) with ten minutes lost after the first quarter hour, its
// samples changed by `edit(samples, gap)` before the preview and analysis.
struct HourWithAGap {
  std::vector<Gap> gaps;
  ReportInput in;
  model::AnalysisResult r;
};
template <typename Edit>
HourWithAGap hour_with_a_gap(Edit edit) {
  sim::ErrorModel m;
  m.output.dropouts = {{900.0, 600.0}};
  sim::Recording rec = effects_hour(m, 3);
  HourWithAGap h;
  h.gaps = sim::remove_dropouts(rec, m.output);
  if (h.gaps.size() == 1) edit(rec.rate_deg_h, h.gaps[0]);
  h.in.preview = preview_record(rec.rate_deg_h, {}, rec.sample_rate_hz, 2000, h.gaps);
  h.r = model::analyze(rec.rate_deg_h, {}, rec.sample_rate_hz, {}, h.gaps);
  return h;
}

TEST(Report, TimePlotShadesTheGapsAndPlacesTheSpikesOnTheFileTime) {
  // Ten minutes lost after the first quarter hour: the time plot shades
  // them, no line crosses them, and a spike after them sits at its true time.
  const HourWithAGap h = hour_with_a_gap([](std::vector<double>& rate, const Gap&) {
    rate[150000] += 60000.0;  // t = 1500 s + 600 s lost = 2100 s
  });
  ASSERT_EQ(h.gaps.size(), 1u);
  const ReportInput& in = h.in;
  const model::AnalysisResult& r = h.r;
  ASSERT_EQ(r.spikes.count, 1);
  const std::vector<Plot> plots = report_plots(r, in);
  const Series* gap = titled(plots[0], "gap (1 found");
  const Series* spike = titled(plots[0], "spike");
  ASSERT_NE(gap, nullptr);
  EXPECT_NEAR(gap->x[0], 899.99 / 3600.0, 1e-9);
  EXPECT_NEAR(gap->x[1], 1500.0 / 3600.0, 1e-9);
  ASSERT_NE(spike, nullptr);
  EXPECT_NEAR(spike->x[0], 2100.0 / 3600.0, 1e-9);
  EXPECT_EQ(titled(plots[0], "bias jump"), nullptr);  // the bias did not move across the gap
  // the preview has a point without values inside the gap
  bool hole = false;
  for (std::size_t k = 0; k < in.preview.time_s.size(); ++k) {
    const double t = in.preview.time_s[k];
    if (t > 900.0 && t < 1500.0) {
      EXPECT_TRUE(std::isnan(in.preview.rate_mean_deg_h[k])) << t;
      hole = true;
    }
  }
  EXPECT_TRUE(hole);
  EXPECT_NEAR(in.preview.time_s.back(), 3600.0, 2.0);
}

TEST(Report, TimePlotMarksABiasJumpAcrossAGapWhereTheRecordResumes) {
  // The same ten minutes lost, and the bias 3000 deg/h higher after them (16
  // times what a 64-sample mean of this noise spreads by): the jump is
  // measured, not levelled, and marked where the record resumes.
  const HourWithAGap h = hour_with_a_gap([](std::vector<double>& rate, const Gap& gap) {
    for (auto i = static_cast<std::size_t>(gap.before_sample); i < rate.size(); ++i) {
      rate[i] += 3000.0;
    }
  });
  ASSERT_EQ(h.gaps.size(), 1u);
  const ReportInput& in = h.in;
  const model::AnalysisResult& r = h.r;
  ASSERT_EQ(r.steps.across_gaps.size(), 1u);
  ASSERT_TRUE(r.steps.across_gaps[0].significant);
  EXPECT_NEAR(r.steps.across_gaps[0].size_deg_h, 3000.0, 300.0);
  EXPECT_TRUE(r.steps.indices.empty());  // not a step within a stretch: nothing levelled
  const std::vector<Plot> plots = report_plots(r, in);
  const Series* jump = titled(plots[0], "bias jump across a gap (1 found");
  ASSERT_NE(jump, nullptr);
  ASSERT_EQ(jump->x.size(), 2u);
  EXPECT_NEAR(jump->x[0], 1500.0 / 3600.0, 1e-9);
  EXPECT_EQ(jump->x[1], jump->x[0]);
  EXPECT_LT(jump->y[0], jump->y[1]);
  ReportOptions in_russian;
  in_russian.language = Language::ru;
  const std::vector<Plot> russian = report_plots(r, in, in_russian);
  EXPECT_NE(titled(russian[0], "скачок смещения нуля через пропуск (найдено: 1"), nullptr);
}

TEST(Report, BiasPlotFollowsTheFittedPolynomial) {
  const Analysed& a = analysed();
  const std::vector<Plot> plots = report_plots(a.result, a.input);
  ASSERT_EQ(plots.size(), 4u);
  const Plot& bias = plots[1];
  ASSERT_EQ(bias.series.size(), 2u);
  const model::SystematicFit& s = *a.result.systematic;
  const Series& fit = bias.series[1];
  for (std::size_t k = 0; k < fit.x.size(); k += 25) {
    double v = 0.0;
    for (std::size_t j = 0; j < s.coefficients.size(); ++j) {
      v += s.coefficients[j] * std::pow(fit.x[k] - s.t_ref_c, static_cast<double>(j));
    }
    EXPECT_NEAR(fit.y[k], v, 1e-9 * (1.0 + std::abs(v)));
  }
  // The truth: 3 deg/h + 0.8 deg/h/degC about the ramp's mean (25 degC).
  ASSERT_GE(s.coefficients.size(), 2u);
  EXPECT_NEAR(s.coefficients[1], 0.8, 0.1);
  EXPECT_LE(bias.series[0].x.size(), 200u);
  EXPECT_GE(bias.series[0].x.size(), 100u);
}

TEST(Preview, BlockMeansAndEnvelope) {
  std::vector<double> rate(10001), temp(10001);
  for (std::size_t k = 0; k < rate.size(); ++k) {
    rate[k] = static_cast<double>(k % 2 == 0 ? k : -static_cast<double>(k));
    temp[k] = 20.0 + 0.001 * static_cast<double>(k);
  }
  const RecordPreview p = preview_record(rate, temp, 10.0, 2000);
  EXPECT_EQ(p.block_samples, 6);  // ceil(10001 / 2000)
  ASSERT_EQ(p.time_s.size(), 1667u);
  // Block 0: samples 0..5 = 0, -1, 2, -3, 4, -5.
  EXPECT_DOUBLE_EQ(p.rate_mean_deg_h[0], -0.5);
  EXPECT_DOUBLE_EQ(p.rate_min_deg_h[0], -5.0);
  EXPECT_DOUBLE_EQ(p.rate_max_deg_h[0], 4.0);
  EXPECT_DOUBLE_EQ(p.time_s[0], 0.25);  // centre of samples 0..5 at 10 Hz
  EXPECT_NEAR(p.temperature_c[0], 20.0025, 1e-12);
  // The last block holds sample 9996..10000.
  EXPECT_DOUBLE_EQ(p.rate_max_deg_h.back(), 10000.0);
  EXPECT_DOUBLE_EQ(p.time_s.back(), 999.8);
  EXPECT_THROW(preview_record(rate, std::vector<double>(3), 10.0), UsageError);
  EXPECT_THROW(preview_record(rate, temp, 0.0), UsageError);
}

TEST(Plot, EqualDecadesSetTheAspectRatio) {
  Plot p;
  p.log_x = p.log_y = true;
  p.equal_decades = true;
  Series s;
  s.x = {1.5, 900.0};  // decades 10^0 .. 10^3
  s.y = {0.2, 8.0};    // decades 10^-1 .. 10^1
  p.series.push_back(s);
  std::string script = detail::gnuplot_script(p);
  EXPECT_NE(script.find("set xrange [1:1000]"), std::string::npos) << script;
  EXPECT_NE(script.find("set yrange [0.1:10]"), std::string::npos) << script;
  EXPECT_NE(script.find("set size ratio 0.666666667"), std::string::npos) << script;
  // One decade of y over six of x would be too flat: y is widened to three.
  p.series[0].x = {1.0, 1e6};
  p.series[0].y = {1.0, 10.0};
  script = detail::gnuplot_script(p);
  EXPECT_NE(script.find("set size ratio 0.5\n"), std::string::npos) << script;
  EXPECT_NE(script.find("set yrange [0.1:100]"), std::string::npos) << script;
  // A guide line does not stretch the ranges; non-positive values break the line.
  Series guide;
  guide.sets_range = false;
  guide.x = {1.0, 1e6};
  guide.y = {1e-9, -1.0};
  p.series.push_back(guide);
  EXPECT_NE(detail::gnuplot_script(p).find("set yrange [0.1:100]"), std::string::npos);
}

TEST(Plot, TitlesAreQuotedForGnuplot) {
  EXPECT_EQ(gnuplot_quote("it's"), "'it''s'");
  EXPECT_EQ(gnuplot_quote("a\nb\\c \"d\""), "'a b\\c \"d\"'");
  Plot p;
  p.title = "K's line; set output '/tmp/x'";
  p.x_label = "tau [s]";
  p.y_label = "T_ref^2";
  Series s;
  s.title = "x<y & z";
  s.x = {1, 2};
  s.y = {3, 4};
  p.series.push_back(s);
  const std::string script = detail::gnuplot_script(p);
  EXPECT_NE(script.find("set title 'K''s line; set output ''/tmp/x'''\n"), std::string::npos)
      << script;
  EXPECT_NE(script.find("noenhanced"), std::string::npos);
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const PlotOutcome out = render_svg(p);
  ASSERT_TRUE(out.svg.has_value()) << out.error;
  EXPECT_NE(out.svg->find("x&lt;y &amp; z"), std::string::npos);
  EXPECT_NE(out.svg->find("T_ref^2"), std::string::npos);
  EXPECT_EQ(out.svg->rfind("<svg", 0), 0u);
}

}  // namespace
}  // namespace foglab::report
