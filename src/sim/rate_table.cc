#include "foglab/sim/rate_table.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <string_view>

#include "foglab/core/error.h"
#include "foglab/core/output_model.h"
#include "foglab/sim/error_model.h"
#include "foglab/sim/generator.h"

namespace foglab::sim {
namespace {

void check_finite(std::string_view name, double value) {
  if (!std::isfinite(value)) {
    throw UsageError(fmt::format("rate table: {} must be finite, got {}", name, value));
  }
}

void check_coefs(std::string_view name, std::span<const double> coefs) {
  for (std::size_t k = 0; k < coefs.size(); ++k) {
    check_finite(fmt::format("{}[{}]", name, k + 1), coefs[k]);
  }
}

void validate(const RateTableGyro& gyro, std::span<const RatePlateau> plan,
              const RateTableOptions& options) {
  if (plan.empty()) throw UsageError("rate table: the plan has no plateau");
  if (!(std::isfinite(options.settle_s) && options.settle_s >= 0.0)) {
    throw UsageError(
        fmt::format("rate table: settle_s must be >= 0 [s], got {}", options.settle_s));
  }
  for (std::size_t p = 0; p < plan.size(); ++p) {
    check_finite(fmt::format("plateau {} rate_deg_s", p + 1), plan[p].rate_deg_s);
    check_finite(fmt::format("plateau {} temperature_c", p + 1), plan[p].temperature_c);
    if (!(std::isfinite(plan[p].duration_s) && plan[p].duration_s > options.settle_s)) {
      throw UsageError(
          fmt::format("rate table: plateau {} lasts {} s, not longer than the "
                      "settle time ({} s): nothing of it could be used",
                      p + 1, plan[p].duration_s, options.settle_s));
    }
  }
  check_finite("scale_factor_lsb_per_deg_s", gyro.scale_factor_lsb_per_deg_s);
  if (gyro.scale_factor_lsb_per_deg_s == 0.0) {
    throw UsageError("rate table: the scale factor must not be 0 [LSB/(deg/s)]");
  }
  check_finite("asymmetry", gyro.asymmetry);
  check_finite("bias_lsb", gyro.bias_lsb);
  check_finite("reference_c", gyro.reference_c);
  check_coefs("scale_factor_temp_coefs", gyro.scale_factor_temp_coefs);
  check_coefs("nonlinearity_coefs", gyro.nonlinearity_coefs);
  check_coefs("bias_temp_coefs_lsb", gyro.bias_temp_coefs_lsb);
}

}  // namespace

double rate_table_output_lsb(const RateTableGyro& gyro, double rate_deg_s, double temperature_c) {
  const OutputModelTerms terms{gyro.scale_factor_lsb_per_deg_s,
                               gyro.scale_factor_temp_coefs,
                               gyro.nonlinearity_coefs,
                               gyro.asymmetry,
                               gyro.bias_lsb,
                               gyro.bias_temp_coefs_lsb};
  const double dT = temperature_c - gyro.reference_c;
  if (gyro.rate_response) {
    return terms.scale_factor * terms.relative_scale_factor(dT) * gyro.rate_response(rate_deg_s) +
           terms.bias_at(dT);
  }
  return terms.output(rate_deg_s, dT);
}

RateTableGyro optics_rate_table_gyro(const Coil& coil, const OpticsOptions& options) {
  constexpr double kRadPerDeg = std::numbers::pi / 180.0;
  // The small-rate slope from a rate a millionth of the range, where sin is linear to 1e-13.
  const double small_deg_s = 1e-6 * coil_numbers(coil).omega_pi2_deg_s;
  const double slope = steady_state_output(coil, small_deg_s * kRadPerDeg, options) / small_deg_s;
  if (!(std::isfinite(slope) && slope != 0.0)) {
    throw UsageError("rate table: the optics' output does not rise with the rate");
  }
  RateTableGyro gyro;
  gyro.scale_factor_lsb_per_deg_s = slope;
  gyro.rate_response = [coil, options, slope](double rate_deg_s) {
    return steady_state_output(coil, rate_deg_s * kRadPerDeg, options) / slope;
  };
  return gyro;
}

namespace {

// The table's motion and the chamber's temperature over the plan (header), at the noise
// record's times: fills every column of `run` but the output.
void table_motion(std::span<const RatePlateau> plan, const RateTableOptions& options,
                  RateTableRecording& run) {
  const std::size_t n = run.time_s.size();
  run.rate_command_deg_s.resize(n);
  run.table_rate_deg_s.resize(n);
  run.temperature_c.resize(n);
  const double temperature_tc_s = options.settle_s / 5.0;
  std::size_t p = 0;
  double start_s = 0.0;
  double previous_rate = 0.0;  // the table starts at rest
  double previous_temperature = plan.front().temperature_c;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = run.time_s[k];
    while (p + 1 < plan.size() && t >= start_s + plan[p].duration_s) {
      // The state at the plateau's end, where the next one starts from.
      const double end = plan[p].duration_s;
      previous_rate = plan[p].rate_deg_s;
      previous_temperature =
          temperature_tc_s > 0.0
              ? plan[p].temperature_c + (previous_temperature - plan[p].temperature_c) *
                                            std::exp(-end / temperature_tc_s)
              : plan[p].temperature_c;
      start_s += plan[p].duration_s;
      ++p;
    }
    const RatePlateau& plateau = plan[p];
    const double into = t - start_s;
    run.rate_command_deg_s[k] = plateau.rate_deg_s;
    run.table_rate_deg_s[k] =
        into < options.settle_s
            ? previous_rate + (plateau.rate_deg_s - previous_rate) * into / options.settle_s
            : plateau.rate_deg_s;
    run.temperature_c[k] =
        temperature_tc_s > 0.0
            ? plateau.temperature_c + (previous_temperature - plateau.temperature_c) *
                                          std::exp(-into / temperature_tc_s)
            : plateau.temperature_c;
  }
}

double total_duration_s(std::span<const RatePlateau> plan) {
  double total_s = 0.0;
  for (const RatePlateau& p : plan) total_s += p.duration_s;
  return total_s;
}

// The random part of one gyro, rate-equivalent in deg/h: a static gyro's record
// (sim::generate()) on noise stream `stream`.
Recording gyro_noise(const RateTableGyro& gyro, double duration_s, const RateTableOptions& options,
                     std::uint64_t stream) {
  ErrorModel noise_only;
  noise_only.noise = gyro.noise;
  GeneratorOptions generator;
  generator.sample_rate_hz = options.sample_rate_hz;
  generator.duration_s = duration_s;
  generator.seed = options.seed;
  generator.stream = stream;
  return generate(noise_only, TemperatureProfile{}, generator);
}

// Eq. (10) with the noise: the gyro's output when the rate about its input axis is
// `sensed` times the table's.
std::vector<double> gyro_output(const RateTableGyro& gyro, const RateTableRecording& motion,
                                double sensed, const Recording& noise) {
  std::vector<double> out(motion.time_s.size());
  for (std::size_t k = 0; k < out.size(); ++k) {
    out[k] =
        rate_table_output_lsb(gyro, sensed * motion.table_rate_deg_s[k], motion.temperature_c[k]) +
        gyro.scale_factor_lsb_per_deg_s * noise.rate_deg_h[k] / 3600.0;
  }
  return out;
}

}  // namespace

RateTableRecording generate_rate_table(const RateTableGyro& gyro, std::span<const RatePlateau> plan,
                                       const RateTableOptions& options) {
  validate(gyro, plan, options);
  const Recording noise = gyro_noise(gyro, total_duration_s(plan), options, 0);
  RateTableRecording run;
  run.sample_rate_hz = options.sample_rate_hz;
  run.time_s = noise.time_s;
  table_motion(plan, options, run);
  run.output_lsb = gyro_output(gyro, run, 1.0, noise);
  return run;
}

std::array<TriadRecording, 3> generate_rate_table_triad(const RateTableTriad& triad,
                                                        std::span<const RatePlateau> plan,
                                                        const RateTableOptions& options) {
  for (int i = 0; i < 3; ++i) {
    validate(triad.gyros[i], plan, options);
    for (int j = 0; j < 3; ++j) {
      if (i != j) {
        check_finite(fmt::format("misalignment_rad[{}][{}]", i, j), triad.misalignment_rad[i][j]);
      }
    }
  }
  const double duration_s = total_duration_s(plan);
  std::array<TriadRecording, 3> runs;
  for (int axis = 0; axis < 3; ++axis) {
    TriadRecording& r = runs[axis];
    r.table_axis = axis;
    for (int i = 0; i < 3; ++i) {
      // Independent noise for each gyro in each mounting.
      const Recording noise = gyro_noise(triad.gyros[i], duration_s, options,
                                         1 + static_cast<std::uint64_t>(3 * axis + i));
      if (i == 0) {
        r.motion.sample_rate_hz = options.sample_rate_hz;
        r.motion.time_s = noise.time_s;
        table_motion(plan, options, r.motion);
      }
      const double sensed = i == axis ? 1.0 : triad.misalignment_rad[i][axis];
      r.output_lsb[i] = gyro_output(triad.gyros[i], r.motion, sensed, noise);
    }
  }
  return runs;
}

std::vector<RatePlateau> standard_rate_table_plan(double full_scale_deg_s, int rates_per_sign,
                                                  std::span<const double> temperatures_c,
                                                  double plateau_s) {
  if (!(std::isfinite(full_scale_deg_s) && full_scale_deg_s > 0.0)) {
    throw UsageError(
        fmt::format("rate table: the full scale must be > 0 [deg/s], got {}", full_scale_deg_s));
  }
  if (rates_per_sign < 1) {
    throw UsageError(
        fmt::format("rate table: at least 1 rate of each sign, got {}", rates_per_sign));
  }
  if (temperatures_c.empty()) throw UsageError("rate table: no temperature given");
  std::vector<RatePlateau> plan;
  for (const double temperature : temperatures_c) {
    // Up, then down: a drift linear in time is then nearly orthogonal to every even function
    // of the rate (the nonlinearity's w^2 term, the asymmetry), which one sweep up would
    // alias. No two neighbouring plateaus share a rate: a plateau is a run of one commanded
    // rate.
    plan.push_back({0.0, plateau_s, temperature});
    for (int k = 1; k <= rates_per_sign; ++k) {
      const double rate = full_scale_deg_s * k / rates_per_sign;
      plan.push_back({rate, plateau_s, temperature});
      plan.push_back({-rate, plateau_s, temperature});
    }
    for (int k = rates_per_sign; k >= 1; --k) {
      const double rate = full_scale_deg_s * k / rates_per_sign;
      plan.push_back({rate, plateau_s, temperature});
      plan.push_back({-rate, plateau_s, temperature});
    }
  }
  return plan;
}

}  // namespace foglab::sim
