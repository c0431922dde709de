#include "foglab/sim/lab2_variants.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "foglab/core/error.h"
#include "generator_internal.h"

namespace foglab::sim {

std::vector<double> raw_temperature_polynomial(const ErrorModel& model, double t_ref_c) {
  // sum_k c_k (T - r)^k = sum_k c_k sum_j C(k, j) T^j (-r)^(k-j), c_0 = bias + input
  std::vector<double> c = {model.bias + model.input_rate};
  c.insert(c.end(), model.temp_coefs.begin(), model.temp_coefs.end());
  std::vector<double> a(c.size(), 0.0);
  for (std::size_t k = 0; k < c.size(); ++k) {
    double binomial = 1.0;  // C(k, j), j from 0
    for (std::size_t j = 0; j <= k; ++j) {
      a[j] += c[k] * binomial * std::pow(-t_ref_c, static_cast<double>(k - j));
      binomial = binomial * static_cast<double>(k - j) / static_cast<double>(j + 1);
    }
  }
  return a;
}

// --- variants ---------------------------------------------------------------------

namespace {

using detail::mix64;  // SplitMix64 (generator_internal.h)

/// A uniform number in [0, 1), a pure function of its arguments.
class Draw {
 public:
  Draw(std::uint64_t seed, int variant, int gyro)
      : base_(mix64(mix64(seed) ^ (static_cast<std::uint64_t>(variant) << 8) ^
                    static_cast<std::uint64_t>(gyro))) {}
  double uniform(int parameter) const {
    return static_cast<double>(mix64(base_ + static_cast<std::uint64_t>(parameter)) >> 11) *
           0x1.0p-53;
  }
  double linear(int parameter, double lo, double hi) const {
    return lo + (hi - lo) * uniform(parameter);
  }
  double log_uniform(int parameter, double lo, double hi) const {
    return lo * std::pow(hi / lo, uniform(parameter));
  }
  double sign(int parameter) const { return uniform(parameter) < 0.5 ? -1.0 : 1.0; }

 private:
  std::uint64_t base_;
};

/// The ranges of one gyro type (see the header).
struct GyroDesign {
  const char* description;
  double sample_rate_hz;
  double duration_s;
  double arw_lo, arw_hi;              // [deg/sqrt(h)]
  double floor_lo, floor_hi;          // [deg/h] 0.664 B
  double bias_lo, bias_hi;            // [deg/h] magnitude
  double c1_lo, c1_hi, c2_lo, c2_hi;  // magnitudes
};

constexpr GyroDesign kFog1{.description =
                               "closed-loop FOG, intermediate grade (1550 nm source, km-long coil, "
                               "phase-ramp feedback)",
                           .sample_rate_hz = 10.0,
                           .duration_s = 3.0 * 3600.0,
                           .arw_lo = 0.006,
                           .arw_hi = 0.02,
                           .floor_lo = 0.02,
                           .floor_hi = 0.06,
                           .bias_lo = 0.5,
                           .bias_hi = 3.0,
                           .c1_lo = 0.15,
                           .c1_hi = 0.4,
                           .c2_lo = 0.005,
                           .c2_hi = 0.02};
constexpr GyroDesign kFog2{
    .description = "open-loop FOG, tactical grade (830 nm source, all-fibre, piezo modulator)",
    .sample_rate_hz = 20.0,
    .duration_s = 2.0 * 3600.0,
    .arw_lo = 0.08,
    .arw_hi = 0.25,
    .floor_lo = 1.0,
    .floor_hi = 2.5,
    .bias_lo = 5.0,
    .bias_hi = 25.0,
    .c1_lo = 2.0,
    .c1_hi = 4.0,
    .c2_lo = 0.05,
    .c2_hi = 0.2};

constexpr double kJitterC = 0.02;
constexpr double kRampSpanC = 10.0;

void fill_answers(Lab2Run& run, const ErrorModel& model) {
  const double fs = run.generator.sample_rate_hz;
  const double duration = run.generator.duration_s;
  run.t_ref_c = run.temperature.reference_c(duration);
  std::vector<double> a = raw_temperature_polynomial(model, run.t_ref_c);
  a.resize(3, 0.0);
  run.polyfit_p = {a[2], a[1], a[0]};
  run.lab_constant_term_deg_h = a[0];
  run.bias_at_t_ref_deg_h = model.bias + model.input_rate;
  run.constant_term_well_conditioned = run.temperature.kind == TemperatureKind::ramp;
  run.usable_tau_min_s = 1.0 / fs;
  run.usable_tau_max_s = std::max(run.usable_tau_min_s, duration / 10.0);
  run.bias_instability = adev_minimum(model.noise, run.usable_tau_min_s, run.usable_tau_max_s);
  run.random_bias_octaves = term_dominance_octaves(
      model.noise, model.noise.gm_sigma > 0.0 ? NoiseTerm::gauss_markov : NoiseTerm::random_walk,
      run.usable_tau_min_s, run.usable_tau_max_s);
}

Lab2Gyro make_gyro(int variant, int gyro, const Lab2Options& options) {
  const GyroDesign& d = gyro == 1 ? kFog1 : kFog2;
  const Draw draw(options.seed, variant, gyro);
  Lab2Gyro g;
  g.gyro = gyro;
  g.name = fmt::format("FOG{}", gyro);
  g.file_name = fmt::format("FOG{}_{}.mat", gyro, variant);
  const bool wiener = (variant + gyro) % 2 == 0;  // FOG1 odd variants, FOG2 even
  g.random_bias = wiener ? RandomBiasProcess::wiener : RandomBiasProcess::gauss_markov;

  ErrorModel& m = g.model;
  NoiseModel& n = m.noise;
  g.arw_deg_sqrt_h = draw.log_uniform(0, d.arw_lo, d.arw_hi);
  n.N = white_noise_of_arw(g.arw_deg_sqrt_h);
  n.B = flicker_coefficient_deg_h(draw.log_uniform(1, d.floor_lo, d.floor_hi));
  // The random bias is placed so that the record shows it (header): its
  // position counts back from the end of the design duration's usable range.
  const double usable_end_s = d.duration_s / 10.0;
  auto rest_avar = [&](double tau) {  // white noise and flicker at tau
    return allan_variance(n, NoiseTerm::white, tau) + allan_variance(n, NoiseTerm::flicker, tau);
  };
  if (wiener) {
    // The random walk's Allan variance K^2 tau / 3 equals the rest's at
    // tau_w and grows past it, so it carries more than half from there on.
    const double tau_w = usable_end_s / std::exp2(draw.linear(2, 2.5, 4.0));
    n.K = std::sqrt(3.0 * rest_avar(tau_w) / tau_w);
  } else {
    // The hump of the Gauss-Markov ADEV (0.62 sigma at 1.89 Tc) well inside
    // the usable range and well above the rest there.
    const double hump_s = usable_end_s / std::exp2(draw.linear(2, 2.0, 3.5));
    n.gm_tc = hump_s / 1.89;
    n.gm_sigma = draw.linear(3, 2.0, 4.0) * std::sqrt(rest_avar(hump_s)) / 0.62;
  }
  m.bias = draw.sign(4) * draw.log_uniform(5, d.bias_lo, d.bias_hi);
  // What the noise wanders over the run (the random bias, the flicker floor
  // three times, the white noise's mean): the ramp's temperature law must
  // stand out of it, so the coefficients are scaled up together if needed.
  const double wander = n.K * std::sqrt(d.duration_s) + n.gm_sigma +
                        3.0 * flicker_floor_deg_h(n.B) + n.N / std::sqrt(d.duration_s);
  const double scale = std::max(1.0, 0.75 * wander / (d.c1_lo * kRampSpanC / 2.0));
  m.temp_coefs = {draw.sign(6) * scale * draw.linear(7, d.c1_lo, d.c1_hi),
                  draw.sign(8) * scale * draw.linear(9, d.c2_lo, d.c2_hi)};
  m.input_rate = 0.0;
  const double t0_c = std::round(draw.linear(10, 22.0, 28.0) * 10.0) / 10.0;

  g.design = fmt::format(
      "{}; random bias: {}; {} Hz for {} h; thermostat at {} degC, ramp {} -> {} degC",
      d.description, wiener ? "Wiener process" : "first-order Gauss-Markov process",
      d.sample_rate_hz, (options.duration_s ? *options.duration_s : d.duration_s) / 3600.0, t0_c,
      t0_c - kRampSpanC / 2.0, t0_c + kRampSpanC / 2.0);

  for (int r = 0; r < 2; ++r) {
    Lab2Run& run = g.runs[static_cast<std::size_t>(r)];
    run.rate_name = fmt::format("Y{}", r + 1);
    run.temperature_name = fmt::format("T{}", r + 1);
    run.temperature.jitter_c = kJitterC;
    if (r == 0) {
      run.temperature.kind = TemperatureKind::constant;
      run.temperature.start_c = t0_c;
      run.temperature.span_c = 0.0;
    } else {
      run.temperature.kind = TemperatureKind::ramp;
      run.temperature.start_c = t0_c - kRampSpanC / 2.0;
      run.temperature.span_c = kRampSpanC;
    }
    run.generator.sample_rate_hz = d.sample_rate_hz;
    run.generator.duration_s = options.duration_s ? *options.duration_s : d.duration_s;
    run.generator.seed = options.seed;
    run.generator.stream = static_cast<std::uint64_t>(100 * variant + 10 * gyro + r + 1);
    fill_answers(run, m);
  }
  // Both runs share fs and duration, hence the usable tau range and the
  // bias instability; the class follows from them.
  g.verdict = classify(g.runs[0].bias_instability.adev_deg_h, g.arw_deg_sqrt_h);
  return g;
}

}  // namespace

Lab2Variant lab2_variant(int variant, const Lab2Options& options) {
  if (variant < 1 || variant > kLab2Variants) {
    throw UsageError(
        fmt::format("lab-2 variant {} does not exist (1..{})", variant, kLab2Variants));
  }
  if (options.duration_s && !(*options.duration_s > 0.0 && std::isfinite(*options.duration_s))) {
    throw UsageError(fmt::format("lab-2 duration must be > 0 s, got {}", *options.duration_s));
  }
  Lab2Variant v;
  v.variant = variant;
  v.seed = options.seed;
  v.gyros = {make_gyro(variant, 1, options), make_gyro(variant, 2, options)};
  return v;
}

std::vector<Lab2Variant> lab2_variants(const Lab2Options& options) {
  std::vector<Lab2Variant> out;
  for (int k = 1; k <= kLab2Variants; ++k) out.push_back(lab2_variant(k, options));
  return out;
}

}  // namespace foglab::sim
