// foglab — the report of a whole IMU (imu.h).
#include "foglab/report/imu.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

#include "foglab/core/numeric.h"
#include "foglab/core/version.h"
#include "foglab/report/report.h"
#include "report_internal.h"

namespace foglab::report {

using namespace detail;

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// The fit's 95 % upper bound on a term it left out (0: none).
double fit_bound(const model::ParameterEstimate& p) {
  if (std::isfinite(p.upper_95) && p.upper_95 > 0.0) return p.upper_95;
  if (std::isfinite(p.ci95_high) && p.ci95_high > 0.0) return p.ci95_high;
  return 0.0;
}

/// "deg/h" or "m/s^2": the unit the axis was analysed in.
std::string unit_of(Sensor sensor) { return std::string(to_string(internal_unit(sensor))); }

/// The axes of one sensor.
std::vector<const ImuAxis*> axes_of(std::span<const ImuAxis> axes, Sensor sensor) {
  std::vector<const ImuAxis*> out;
  for (const ImuAxis& a : axes) {
    if (a.sensor == sensor && a.result != nullptr) out.push_back(&a);
  }
  return out;
}

/// The root mean square of `values` (the mean noise power's amplitude).
double rms(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double v : values) sum += v * v;
  return values.empty() ? kNaN : std::sqrt(sum / static_cast<double>(values.size()));
}

}  // namespace

double kalibr_factor(Sensor sensor) {
  // deg/h -> rad/s; an accelerometer is analysed in m/s^2 already.
  return sensor == Sensor::gyroscope ? 1.0 / kDegPerRad / kSecondsPerHour : 1.0;
}

FilterNoise filter_noise(const model::AnalysisResult& r, Sensor sensor) {
  FilterNoise f;
  f.white_low = f.white_high = f.random_walk_low = f.random_walk_high = kNaN;
  const std::string u = unit_of(sensor);

  // White noise: the fit's N, else a graphical reading, else its bound.
  const model::ParameterEstimate& pn = r.noise.N;
  if (pn.status == model::TermStatus::resolved) {
    f.white = pn.value;
    f.white_low = pn.ci95_low;
    f.white_high = pn.ci95_high;
    f.white_resolved = true;
    f.white_source = fmt::format("N = {:.6g} {}/sqrt(Hz), 95 % interval [{}, {}]", f.white, u,
                                 g(pn.ci95_low), g(pn.ci95_high));
  } else if (r.psd_readings.N) {
    f.white = *r.psd_readings.N;
    f.white_source = fmt::format(
        "N = {:.6g} {}/sqrt(Hz) read off the PSD (the fit did not resolve N)", f.white, u);
  } else if (r.adev_readings.N) {
    f.white = *r.adev_readings.N;
    f.white_source = fmt::format(
        "N = {:.6g} {}/sqrt(Hz) read off the ADEV (the fit did not resolve N)", f.white, u);
  } else if (std::isfinite(pn.upper_95)) {
    f.white = pn.upper_95;
    f.white_source =
        fmt::format("N < {:.6g} {}/sqrt(Hz): 95 % upper bound, N not resolved", f.white, u);
  } else {
    f.white_source = "N could not be estimated from this record: 0 written, set it by hand";
  }

  // Bias random walk: the fit's K, else its 95 % upper bound, else the
  // driving noise of a Gauss-Markov bias.
  const model::ParameterEstimate& pk = r.noise.K;
  const NoiseModel& m = r.noise.model;
  if (pk.status == model::TermStatus::resolved) {
    f.random_walk = pk.value;
    f.random_walk_low = pk.ci95_low;
    f.random_walk_high = pk.ci95_high;
    f.random_walk_resolved = true;
    f.random_walk_source = fmt::format("K = {:.6g} {}/sqrt(s), 95 % interval [{}, {}]",
                                       f.random_walk, u, g(pk.ci95_low), g(pk.ci95_high));
  } else if (const double bound = fit_bound(pk); bound > 0.0) {
    // The random walk's Allan deviation alone, K sqrt(tau/3), cannot stand above the
    // record's 95 % upper limit at any tau: a bound the data set directly, tighter than the
    // fit's when another term (a ramp) took the long taus.
    double adev_bound = kInfinity, adev_tau = kNaN;
    const stats::AllanResult& a = r.allan;
    for (std::size_t k = 0; k < a.tau_s.size() && k < a.ci95_high.size(); ++k) {
      const double b = a.ci95_high[k] / std::sqrt(a.tau_s[k] / 3.0);
      if (std::isfinite(b) && b < adev_bound) adev_bound = b, adev_tau = a.tau_s[k];
    }
    if (adev_bound < bound) {
      f.random_walk = adev_bound;
      f.random_walk_source = fmt::format(
          "K < {:.6g} {}/sqrt(s): not resolved by this record; bounded by the Allan "
          "deviation's 95 % upper limit at tau = {} s, which a random walk alone would exceed "
          "(the fit's own bound, {:.6g}, is looser; bias instability {} {} at {} s)",
          adev_bound, u, g(adev_tau), bound, g(r.bias_instability_deg_h), u,
          g(r.bias_instability_tau_s));
    } else {
      f.random_walk = bound;
      f.random_walk_source = fmt::format(
          "K < {:.6g} {}/sqrt(s): the 95 % upper bound, K is not resolved by this record "
          "(bias instability {} {} at {} s is the bias's drift over that time)",
          bound, u, g(r.bias_instability_deg_h), u, g(r.bias_instability_tau_s));
    }
  } else if (m.gm_sigma > 0.0 && m.gm_tc > 0.0) {
    f.random_walk = m.gm_sigma * std::sqrt(2.0 / m.gm_tc);
    f.random_walk_source = fmt::format(
        "no Wiener term and no bound on it: the driving noise sigma*sqrt(2/Tc) = {:.6g} "
        "{}/sqrt(s) of the Gauss-Markov bias (sigma {} {}, Tc {} s)",
        f.random_walk, u, g(m.gm_sigma), u, g(m.gm_tc));
  } else {
    f.random_walk_source = "K could not be bounded by this record: 0 written, set it by hand";
  }
  if (r.noise.random_bias_process == RandomBiasProcess::gauss_markov) {
    f.random_walk_source += fmt::format(
        "; the random bias is Gauss-Markov (sigma {} {}, Tc {} s), which Kalibr "
        "cannot represent",
        g(m.gm_sigma), u, g(m.gm_tc));
  }
  return f;
}

namespace {

/// The root mean square over a sensor's axes of their white noise and
/// random walk, in Kalibr's units.
std::pair<double, double> sensor_kalibr_values(std::span<const ImuAxis> axes, Sensor sensor) {
  std::vector<double> white, walk;
  for (const ImuAxis* a : axes_of(axes, sensor)) {
    const FilterNoise f = filter_noise(*a->result, sensor);
    white.push_back(f.white * kalibr_factor(sensor));
    walk.push_back(f.random_walk * kalibr_factor(sensor));
  }
  return {rms(white), rms(walk)};
}

}  // namespace

KalibrValues kalibr_values(std::span<const ImuAxis> axes) {
  KalibrValues v;
  std::tie(v.gyroscope_noise_density, v.gyroscope_random_walk) =
      sensor_kalibr_values(axes, Sensor::gyroscope);
  std::tie(v.accelerometer_noise_density, v.accelerometer_random_walk) =
      sensor_kalibr_values(axes, Sensor::accelerometer);
  return v;
}

std::string kalibr_imu_yaml(std::span<const ImuAxis> axes, std::string_view file_name,
                            double update_rate_hz, std::string_view rostopic) {
  const double dt = 1.0 / update_rate_hz;
  std::string y = fmt::format(
      "# Kalibr IMU noise model (imu.yaml) of '{}', written by foglab {}.\n"
      "# Continuous-time values (Kalibr's convention), from the noise model fitted to each\n"
      "# axis's Allan variance: the white-noise density N and the bias random walk K. One\n"
      "# value per sensor: the root mean square over its axes (listed below). A filter\n"
      "# running at the sample interval dt = {:.6g} s uses the discrete values\n"
      "# sigma_d = noise_density / sqrt(dt) and sigma_bd = random_walk * sqrt(dt) (Kalibr's\n"
      "# IMU noise model page); they are given in the comments. Kalibr advises inflating\n"
      "# these for real-world use (vibration, temperature).\n",
      file_name, version(), dt);

  struct Field {
    Sensor sensor;
    const char* prefix;
    const char* density_unit;
    const char* walk_unit;
  };
  static constexpr Field kFields[] = {
      {Sensor::accelerometer, "accelerometer", "m/s^2/sqrt(Hz)", "m/s^3/sqrt(Hz)"},
      {Sensor::gyroscope, "gyroscope", "rad/s/sqrt(Hz)", "rad/s^2/sqrt(Hz)"},
  };
  for (const Field& field : kFields) {
    const std::vector<const ImuAxis*> own = axes_of(axes, field.sensor);
    y += fmt::format("\n# {}\n", field.sensor == Sensor::gyroscope ? "Gyroscope" : "Accelerometer");
    if (own.empty()) {
      y += fmt::format(
          "# No {} in this recording: these fields are not measured.\n"
          "#{}_noise_density: 0.0  # [{}]\n#{}_random_walk: 0.0  # [{}]\n",
          to_string(field.sensor), field.prefix, field.density_unit, field.prefix, field.walk_unit);
      continue;
    }
    const double factor = kalibr_factor(field.sensor);
    std::string white_axes, walk_axes;
    for (const ImuAxis* a : own) {
      const FilterNoise f = filter_noise(*a->result, field.sensor);
      white_axes += fmt::format("#   {}: {:.6g} [{}]; {}\n", a->channel, f.white * factor,
                                field.density_unit, f.white_source);
      walk_axes += fmt::format("#   {}: {:.6g} [{}]; {}\n", a->channel, f.random_walk * factor,
                               field.walk_unit, f.random_walk_source);
    }
    const auto [density, random_walk] = sensor_kalibr_values(axes, field.sensor);
    y += fmt::format("# white noise of each axis:\n{}", white_axes);
    y += fmt::format("{}_noise_density: {:.9g}  # [{}] continuous; discrete {:.6g} per sample\n",
                     field.prefix, density, field.density_unit, density / std::sqrt(dt));
    y += fmt::format("# bias random walk of each axis:\n{}", walk_axes);
    y += fmt::format("{}_random_walk: {:.9g}  # [{}] continuous; discrete {:.6g} per sample\n",
                     field.prefix, random_walk, field.walk_unit, random_walk * std::sqrt(dt));
  }
  y += fmt::format("\nrostopic: {}  # the IMU's ROS topic\n", rostopic);
  y +=
      fmt::format("update_rate: {:.9g}  # [Hz] the sample rate of the recording\n", update_rate_hz);
  return y;
}

std::string imu_markdown(std::span<const ImuAxis> axes, std::string_view title) {
  std::string md = fmt::format("# {}\n\n", title);
  md += fmt::format(
      "{} axes analysed. Gyroscopes in deg/h (N deg/h/sqrt(Hz), ARW deg/sqrt(h), K "
      "deg/h/sqrt(s)), accelerometers in m/s^2 (N m/s^2/sqrt(Hz), VRW m/s/sqrt(h), K "
      "m/s^2/sqrt(s) = m/s^3/sqrt(Hz)); 95 % intervals. The accuracy class (lab manual, Table "
      "1) applies to gyroscopes only. The short-tau trend: the taus whose Allan deviation "
      "trends over the run, block by block (each axis's notes and report say more).\n\n",
      axes.size());
  md +=
      "| axis | sensor | N [95 %] | ARW / VRW | bias instability (ADEV min) | K [95 %] | "
      "random bias | class | short-tau trend over the run |\n";
  md += "|---|---|---|---|---|---|---|---|---|\n";
  for (const ImuAxis& a : axes) {
    const model::AnalysisResult& r = *a.result;
    const std::string u = unit_of(a.sensor);
    const ParameterText n = parameter_text(r.noise.N, Language::en),
                        k = parameter_text(r.noise.K, Language::en);
    const bool gyro = a.sensor == Sensor::gyroscope;
    const std::string walk =
        gyro ? fmt::format("{} deg/sqrt(h)", g(r.arw_deg_sqrt_h))
             : fmt::format("{} m/s/sqrt(h)", g(velocity_random_walk_m_s_sqrt_h(r.noise.model.N)));
    const std::string bias =
        gyro ? fmt::format("{} deg/h at {} s", g(r.bias_instability_deg_h),
                           g(r.bias_instability_tau_s))
             : fmt::format("{} m/s^2 ({} mg) at {} s", g(r.bias_instability_deg_h),
                           g(r.bias_instability_deg_h / kStandardGravity * 1000.0),
                           g(r.bias_instability_tau_s));
    md += fmt::format(
        "| {} | {} | {} {} {}/sqrt(Hz) | {} | {} | {} {} {}/sqrt(s) | {} | {} | {} |\n", a.channel,
        to_string(a.sensor), n.value, n.interval, u, walk, bias, k.value, k.interval, u,
        to_string(r.noise.random_bias_process),
        gyro ? std::string(to_string(r.verdict.accuracy_class)) : "-", drift_cell(r.allan_drift));
  }

  md += "\n## For a navigation filter\n\n";
  md +=
      "Continuous-time densities (Kalibr's units) and the standard deviation per sample at "
      "the record's rate: white noise sigma_d = density x sqrt(rate), bias random walk "
      "sigma_bd = K / sqrt(rate).\n\n";
  md += "| axis | rate [Hz] | noise density | per sample | bias random walk | per sample |\n";
  md += "|---|---|---|---|---|---|\n";
  for (const ImuAxis& a : axes) {
    const model::AnalysisResult& r = *a.result;
    const FilterNoise f = filter_noise(r, a.sensor);
    const double factor = kalibr_factor(a.sensor);
    const bool gyro = a.sensor == Sensor::gyroscope;
    const std::string value_unit = gyro ? "rad/s" : "m/s^2";
    const std::string walk_unit = gyro ? "rad/s^2/sqrt(Hz)" : "m/s^3/sqrt(Hz)";
    const double fs = r.sample_rate_hz;
    md +=
        fmt::format("| {} | {} | {} {}/sqrt(Hz){} | {} {} | {}{} {} | {} {} |\n", a.channel, g(fs),
                    g(f.white * factor), value_unit, f.white_resolved ? "" : " (not fitted)",
                    g(f.white * factor * std::sqrt(fs)), value_unit,
                    f.random_walk_resolved ? "" : "< ", g(f.random_walk * factor), walk_unit,
                    g(f.random_walk * factor / std::sqrt(fs)), gyro ? "rad/s" : "m/s^2");
  }
  for (const ImuAxis& a : axes) {
    if (a.result->notes.empty()) continue;
    md += fmt::format("\nNotes on {}:\n\n", a.channel);
    for (const Message& n : a.result->notes)
      md += "- " + in_sensor_units(n.text(), a.sensor) + "\n";
  }
  return md;
}

std::vector<Plot> imu_allan_plots(std::span<const ImuAxis> axes, std::string_view title) {
  static constexpr const char* kColours[] = {kRed, kGreen, kBlue, kOrange, kPurple, kYellow};
  std::vector<Plot> plots;
  for (const Sensor sensor : {Sensor::gyroscope, Sensor::accelerometer}) {
    const std::vector<const ImuAxis*> own = axes_of(axes, sensor);
    if (own.empty()) continue;
    Plot plot;
    plot.title =
        fmt::format("{}: overlapping Allan deviation of the {}s", title, to_string(sensor));
    plot.x_label = "tau [s]";
    plot.y_label = fmt::format("Allan deviation [{}]", unit_of(sensor));
    plot.log_x = plot.log_y = true;
    plot.equal_decades = true;
    plot.headroom_decades = 1;
    for (std::size_t i = 0; i < own.size(); ++i) {
      const model::AnalysisResult& r = *own[i]->result;
      const char* colour = kColours[i % std::size(kColours)];
      Series dev;
      dev.title = own[i]->channel;
      dev.style = SeriesStyle::linespoints;
      dev.color = colour;
      dev.x = r.allan.tau_s;
      dev.y = r.allan.dev;
      plot.series.push_back(std::move(dev));
      Series fit;
      fit.title = own[i]->channel + " model";
      fit.color = colour;
      fit.dash_type = 2;
      fit.sets_range = false;
      fit.x = r.allan.tau_s;
      for (const double tau : r.allan.tau_s) {
        fit.y.push_back(std::sqrt(model::fitted_allan_variance(r.noise, tau)));
      }
      plot.series.push_back(std::move(fit));
    }
    plots.push_back(std::move(plot));
  }
  return plots;
}

std::string imu_html(std::span<const ImuAxis> axes, std::span<const Report> axis_reports,
                     std::string_view title, const ReportOptions& options) {
  std::string h =
      "<h2>Summary</h2>\n<p>Gyroscopes in deg/h, accelerometers in m/s^2; 95 % "
      "intervals. The accuracy class (lab manual, Table 1) applies to gyroscopes "
      "only. The short-tau trend: the taus whose Allan deviation trends over the run, "
      "block by block (each axis's report says more).</p>\n<table>\n<tr>" +
      th("axis") + th("sensor") + th("N") + th("95 % interval") + th("unit") + th("ARW / VRW") +
      th("bias instability (ADEV minimum)") + th("K") + th("random bias") + th("class") +
      th("short-tau trend over the run") + "</tr>\n";
  for (const ImuAxis& a : axes) {
    const model::AnalysisResult& r = *a.result;
    const bool gyro = a.sensor == Sensor::gyroscope;
    const ParameterText n = parameter_text(r.noise.N, Language::en),
                        k = parameter_text(r.noise.K, Language::en);
    const std::string u = unit_of(a.sensor);
    h += "<tr>" + td(a.channel) + td(to_string(a.sensor)) + td(n.value) + td(n.interval) +
         td(u + "/sqrt(Hz)") +
         td(gyro ? fmt::format("{} deg/sqrt(h)", g(r.arw_deg_sqrt_h))
                 : fmt::format("{} m/s/sqrt(h)",
                               g(velocity_random_walk_m_s_sqrt_h(r.noise.model.N)))) +
         td(fmt::format("{} {} at {} s", g(r.bias_instability_deg_h), u,
                        g(r.bias_instability_tau_s))) +
         td(fmt::format("{} {} {}/sqrt(s)", k.value, k.interval, u)) +
         td(to_string(r.noise.random_bias_process)) +
         td(gyro ? std::string(to_string(r.verdict.accuracy_class)) : "-") +
         td(drift_cell(r.allan_drift)) + "</tr>\n";
  }
  h += "</table>\n";

  const std::vector<Plot> plots = imu_allan_plots(axes, title);
  std::vector<FigureSpec> specs;
  for (const Plot& p : plots) {
    const bool gyro = p.y_label.find("deg/h") != std::string::npos;
    specs.push_back({gyro ? "imu_gyro" : "imu_accel",
                     fmt::format("Overlapping Allan deviation of every {} axis, with each "
                                 "axis's fitted model (dashed), log-log with equal decades.",
                                 gyro ? "gyroscope" : "accelerometer")});
  }
  ReportOptions o = options;
  o.id_prefix = options.id_prefix + "imu";
  const RenderedFigures drawn = render_figures(plots, specs, o);
  if (drawn.skipped) {
    h += "<p class=\"warn\">" + html_escape(drawn.note) + "</p>\n";
  } else {
    for (const Figure& f : drawn.figures) {
      h += figure_html(f);
    }
  }
  return html_document(axis_reports, title, h);
}

}  // namespace foglab::report
