#include "foglab/sim/presets.h"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "foglab/core/error.h"
#include "foglab/sim/lab2_variants.h"

namespace foglab::sim {
namespace {

/// A preset from datasheet figures: ARW [deg/sqrt(h)] (or N directly) and
/// the bias instability [deg/h]. The class follows Table 1 from those two
/// numbers (the worse of the two criteria).
Preset from_datasheet(std::string name, std::string description, double n_deg_h_sqrt_hz,
                      double bi_deg_h, double sample_rate_hz) {
  Preset p;
  p.name = std::move(name);
  p.model.noise.N = n_deg_h_sqrt_hz;
  p.model.noise.B = flicker_coefficient_deg_h(bi_deg_h);
  p.sample_rate_hz = sample_rate_hz;
  const double arw = arw_deg_sqrt_h(n_deg_h_sqrt_hz);
  const ClassVerdict verdict = classify(bi_deg_h, arw);
  p.accuracy_class = std::string(to_string(verdict.accuracy_class));
  p.description = fmt::format(
      "{} Model: N = {:.4g} deg/h/sqrt(Hz) (ARW {:.4g} deg/sqrt(h)), B = BI/0.664 = "
      "{:.4g} deg/h (BI {:.4g} deg/h); no rate random walk, Gauss-Markov, ramp, "
      "quantisation, bias or temperature terms (not on the datasheet; add them with "
      "options). Table 1 class: {} (by BI {}, by ARW {}).",
      description, p.model.noise.N, arw, p.model.noise.B, bi_deg_h, p.accuracy_class,
      to_string(verdict.by_bias_instability), to_string(verdict.by_arw));
  return p;
}

std::vector<Preset> make_presets() {
  std::vector<Preset> out;
  // KVH open-loop FOGs, lab manual Fig. 15 (datasheet maxima taken as values).
  out.push_back(from_datasheet("kvh-dsp-3000",
                               "KVH DSP-3000 open-loop FOG (lab manual Fig. 15): ARW <= 0.067 "
                               "deg/sqrt(h), bias instability <= 1 deg/h; limits taken as values.",
                               white_noise_of_arw(0.067), 1.0, 100.0));
  out.push_back(
      from_datasheet("kvh-dsp-1750",
                     "KVH DSP-1750 open-loop FOG (lab manual Fig. 15): ARW <= 0.013 "
                     "deg/sqrt(h), bias instability <= 0.1 deg/h; limits taken as values.",
                     white_noise_of_arw(0.013), 0.1, 100.0));
  out.push_back(from_datasheet("kvh-dsp-1760",
                               "KVH DSP-1760 open-loop FOG (lab manual Fig. 15): ARW <= 0.012 "
                               "deg/sqrt(h), bias instability <= 0.05 deg/h; limits taken as "
                               "values.",
                               white_noise_of_arw(0.012), 0.05, 100.0));
  // Closed-loop FOGs of the manual's Table 3: "noise of the output signal"
  // in (deg/h)/sqrt(Hz) is N; "random bias drift at fixed temperature (1 sigma)"
  // is taken as the bias instability. KIND 11-222 (no noise figure) is left out.
  const char* t3 = "lab manual Table 3: output noise {} (deg/h)/sqrt(Hz) taken as N; random bias "
                   "drift at fixed temperature {} deg/h ({}) taken as the bias instability.";
  out.push_back(from_datasheet(
      "fog-600s", fmt::format("FOG 600S, FOG Photonics (Hong Kong), 1500 m coil; {}",
                              fmt::format(fmt::runtime(t3), "<= 0.7", "<= 0.005", "1 sigma")),
      0.7, 0.005, 100.0));
  out.push_back(from_datasheet(
      "oius-2000", fmt::format("OIUS-2000, Optolink (Russia), 2000 m coil; {}",
                               fmt::format(fmt::runtime(t3), "<= 0.03", "<= 0.005", "1 sigma")),
      0.03, 0.005, 100.0));
  out.push_back(from_datasheet(
      "oius-1000", fmt::format("OIUS-1000, Optolink (Russia), 1000 m coil; {}",
                               fmt::format(fmt::runtime(t3), "<= 0.07", "<= 0.01", "1 sigma")),
      0.07, 0.01, 100.0));
  out.push_back(from_datasheet(
      "vog-120",
      fmt::format("VOG-120, PNPPK (Russia), 1000 m coil; {} The quoted range 0.02...0.05 deg/h "
                  "is represented by its middle, 0.035 deg/h.",
                  fmt::format(fmt::runtime(t3), "<= 0.18", "0.02...0.05", "1 sigma")),
      0.18, 0.035, 100.0));
  out.push_back(from_datasheet(
      "fog-120", fmt::format("FOG 120, iXblue (France), 2000 m coil; {}",
                             fmt::format(fmt::runtime(t3), "<= 0.072", "<= 0.01", "1 sigma")),
      0.072, 0.01, 100.0));
  out.push_back(from_datasheet(
      "fog-1000",
      fmt::format("FOG 1000, Northrop Grumman (USA), 1000 m coil; {}",
                  fmt::format(fmt::runtime(t3), "<= 0.04", "0.005", "confidence not stated")),
      0.04, 0.005, 100.0));
  out.push_back(from_datasheet(
      "elektropribor-fog",
      fmt::format("FOG of CSRI Elektropribor (Russia), 2000 m coil; {}",
                  fmt::format(fmt::runtime(t3), "<= 0.04", "<= 0.01", "1 sigma")),
      0.04, 0.01, 100.0));
  // One archetype per Table 1 class, at the geometric middle of the class's
  // bias-instability and ARW ranges (open-ended ranges: half the bound for
  // strategic, 3x the bound for consumer ARW).
  struct Archetype {
    const char* cls;
    double bi;   // [deg/h]
    double arw;  // [deg/sqrt(h)]
    const char* ranges;
  };
  const Archetype archetypes[] = {
      {"strategic", 0.0005, 0.00015, "BI < 0.001 deg/h, ARW < 0.0003 deg/sqrt(h)"},
      {"navigation", 0.00316, 0.00122, "BI 0.001..0.01 deg/h, ARW 0.0003..0.005 deg/sqrt(h)"},
      {"intermediate", 0.1, 0.0158, "BI 0.01..1 deg/h, ARW 0.005..0.05 deg/sqrt(h)"},
      {"tactical", 3.16, 0.158, "BI 1..10 deg/h, ARW 0.05..0.5 deg/sqrt(h)"},
      {"consumer", 100.0, 1.5, "BI 10..1000 deg/h, ARW > 0.5 deg/sqrt(h)"},
  };
  for (const Archetype& a : archetypes) {
    out.push_back(from_datasheet(
        fmt::format("class-{}", a.cls),
        fmt::format("Archetype of the {} class of the lab manual's Table 1 ({}): BI {} deg/h "
                    "and ARW {} deg/sqrt(h), the geometric middle of each range (an open range "
                    "takes half its upper or three times its lower bound).",
                    a.cls, a.ranges, a.bi, a.arw),
        white_noise_of_arw(a.arw), a.bi, 100.0));
  }
  return out;
}

}  // namespace

const std::vector<Preset>& presets() {
  static const std::vector<Preset> all = make_presets();
  return all;
}

const Preset& find_preset(std::string_view name) {
  for (const Preset& p : presets()) {
    if (p.name == name) return p;
  }
  std::string names;
  for (const Preset& p : presets()) names += (names.empty() ? "" : ", ") + p.name;
  throw UsageError(fmt::format("unknown preset '{}'; the presets are: {}", name, names));
}

ImuModel mems_imu_model() {
  ImuModel imu;
  imu.name = "mems-imu";
  imu.description =
      "MEMS IMU at 400 Hz after the Bosch BMI088 datasheet (gyroscope 0.0066 deg/s/sqrt(Hz), "
      "bias instability 14.5 deg/h; accelerometer 230 ug/sqrt(Hz), 27 ug); bias random walks "
      "assumed; axes differ by up to 15 %; gravity on accel_z";
  imu.sample_rate_hz = 400.0;
  // Each axis's scale against the datasheet figures: a real triad's axes
  // are alike, not equal.
  constexpr double kAxisScale[3] = {1.0, 0.9, 1.15};
  for (std::size_t a = 0; a < 3; ++a) {
    ErrorModel& gyro = imu.axes[a];
    gyro.noise.N = 0.0066 * 3600.0 * kAxisScale[a];     // deg/h/sqrt(Hz)
    gyro.noise.B = 14.5 / 0.664 * kAxisScale[2 - a];    // deg/h: ADEV floor 14.5 deg/h
    gyro.noise.K = 2.0 * kAxisScale[a];                 // deg/h/sqrt(s)
    gyro.bias = 36.0 * (static_cast<double>(a) - 1.0);  // deg/h: -36, 0, +36
    ErrorModel& accel = imu.axes[3 + a];
    accel.noise.N = 230e-6 * 9.80665 * kAxisScale[2 - a];                   // m/s^2/sqrt(Hz)
    accel.noise.B = 2.7e-4 / 0.664 * kAxisScale[a];                         // m/s^2
    accel.noise.K = 4e-5 * kAxisScale[2 - a];                               // m/s^2/sqrt(s)
    accel.bias = a == 2 ? 9.80665 : 0.02 * (static_cast<double>(a) - 0.5);  // m/s^2
  }
  return imu;
}

}  // namespace foglab::sim
