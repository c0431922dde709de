// foglab — lab 1's experiments on the optics model (lab1.h).
#include "foglab/sim/lab1.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "foglab/core/error.h"
#include "optics_internal.h"

namespace foglab::sim {
namespace {

/// A trace stride that keeps about `points` samples of `samples` and is
/// not a multiple of the samples per transit (so the decimated samples
/// visit every phase of the modulation).
std::int64_t stride_for(std::int64_t samples, int points, int samples_per_transit) {
  std::int64_t stride = std::max<std::int64_t>(1, samples / std::max(1, points));
  while (stride > 1 && stride % samples_per_transit == 0) ++stride;
  if (stride % 2 == 0 && samples_per_transit % 2 == 0) ++stride;
  return stride;
}

}  // namespace

Lab1Result run_lab1(const Coil& coil, const Lab1Options& o) {
  if (o.ramp_periods < 10 || o.window_periods < 1 || o.trace_points < 10 ||
      o.closed_trace_periods < 2) {
    throw UsageError(
        fmt::format("lab 1: ramp_periods >= 10, window_periods >= 1, trace_points >= 10 and "
                    "closed_trace_periods >= 2 are needed, got {}, {}, {} and {}",
                    o.ramp_periods, o.window_periods, o.trace_points, o.closed_trace_periods));
  }
  if (!(o.off_frequency_ratio > 0.0 && o.off_frequency_ratio <= 1.0) ||
      !(o.ramp_range_fraction > 0.0)) {
    throw UsageError(fmt::format(
        "lab 1: the off-frequency ratio must be in (0, 1] and the ramp range positive, got {} "
        "and {}",
        o.off_frequency_ratio, o.ramp_range_fraction));
  }
  Lab1Result r;
  r.coil = coil;
  r.numbers = coil_numbers(coil);
  const double omega = r.numbers.omega_pi2_rad_s;
  const double period_s = 1.0 / r.numbers.modulation_frequency_hz;
  const int m = o.optics.samples_per_transit;
  const auto ramp_samples = static_cast<std::int64_t>(o.ramp_periods) * 2 * m;

  // 2.4-2.9: the open loop under a ramp over +-Omega_pi/2, each modulation.
  const Modulation kinds[] = {Modulation::none, Modulation::square, Modulation::sine};
  for (std::size_t k = 0; k < 3; ++k) {
    Lab1OpenLoopRun& run = r.open_loop[k];
    run.modulation = kinds[k];
    OpticsOptions opt = o.optics;
    opt.modulation = kinds[k];
    opt.modulation_frequency_hz = 0.0;
    opt.trace_stride = stride_for(ramp_samples, o.trace_points, m);
    opt.trace_limit = static_cast<std::size_t>(o.trace_points) + 1;
    run.ramp = simulate_open_loop(coil, RateInput::ramp(-omega, omega, o.ramp_periods * period_s),
                                  o.ramp_periods * period_s, opt);
    opt.trace_stride = 1;
    opt.trace_limit = static_cast<std::size_t>(o.window_periods) * 2 * m;
    run.window = simulate_open_loop(coil, RateInput::constant(o.window_rate_fraction * omega),
                                    o.window_periods * period_s, opt);
    const double gamma = run.ramp.gamma;
    run.full_scale = kinds[k] == Modulation::sine ? std::abs(steady_state_output(coil, omega, opt))
                                                  : 2.0 * gamma;
    run.worst_deviation_of_full_scale = std::numeric_limits<double>::quiet_NaN();
    if (kinds[k] != Modulation::none) {
      SweepOptions analytic = o.sweep;
      analytic.method = SweepMethod::analytic;
      OpticsOptions so = opt;
      so.trace_stride = 0;
      const SweepResult time = sweep_open_loop(coil, omega, so, o.sweep);
      const SweepResult theory = sweep_open_loop(coil, omega, so, analytic);
      double worst = 0.0;
      for (std::size_t i = 0; i < time.outputs.size(); ++i) {
        worst = std::max(worst, std::abs(time.outputs[i] - theory.outputs[i]));
      }
      run.worst_deviation_of_full_scale = worst / run.full_scale;
      if (kinds[k] == Modulation::square) {
        r.sweep_square = time;
        r.sweep_square_analytic = theory;
      } else {
        r.sweep_sine = time;
      }
    }
  }

  // 3.6: the 30 % range, by the time simulation and analytically.
  OpticsOptions square = o.optics;
  square.modulation = Modulation::square;
  square.modulation_frequency_hz = 0.0;
  square.trace_stride = 0;
  r.range_30_rad_s = range_for_nonlinearity(coil, 30.0, square, o.sweep);
  SweepOptions analytic = o.sweep;
  analytic.method = SweepMethod::analytic;
  r.range_30_analytic_rad_s = range_for_nonlinearity(coil, 30.0, square, analytic);

  // 4.2: the closed and the open loop under a ramp well beyond Omega_pi/2.
  const double ramp_s = o.ramp_periods * period_s;
  const RateInput ramp = RateInput::ramp(0.0, o.ramp_range_fraction * omega, ramp_s);
  r.closed_ramp = simulate_closed_loop(coil, ramp, ramp_s, square, o.loop);
  r.open_ramp = simulate_open_loop(coil, ramp, ramp_s, square);
  OpticsOptions every_sample = square;  // the staircase's steps, each transit time
  every_sample.trace_stride = 1;
  every_sample.trace_limit = static_cast<std::size_t>(o.closed_trace_periods) * 2 * m + 1;
  for (std::size_t k = 0; k < r.closed_traces.size(); ++k) {
    r.closed_traces[k] =
        simulate_closed_loop(coil, RateInput::constant(o.closed_trace_rate_fractions[k] * omega),
                             o.closed_trace_periods * period_s, every_sample, o.loop);
  }

  // 5.1-5.4: the closed-loop sweep.
  r.sweep_closed = sweep_closed_loop(coil, omega, square, o.loop, o.sweep);

  // Off the proper frequency: spikes and the loss of signal.
  OpticsOptions off = square;
  off.modulation_frequency_hz = o.off_frequency_ratio * r.numbers.modulation_frequency_hz;
  const double off_period_s = 1.0 / off.modulation_frequency_hz;
  const double rate = o.off_frequency_rate_fraction * omega;
  const double run_s = 100.0 * off_period_s;
  const OpticsResult proper = simulate_open_loop(coil, RateInput::constant(rate), run_s, square);
  off.trace_stride = 1;
  off.trace_limit = static_cast<std::size_t>(
      std::ceil(o.window_periods * off_period_s / proper.sample_interval_s));
  r.off_frequency = simulate_open_loop(coil, RateInput::constant(rate), run_s, off);
  r.off_frequency_signal_ratio = detail::mean_of_last(r.off_frequency.periods.demodulated, 50) /
                                 detail::mean_of_last(proper.periods.demodulated, 50);
  // Theory with the gate: below f_m the phase difference is +-pi/2 for the
  // first tau0 of each half period H, 0 for the rest (where the two halves
  // cancel), and the first g = gate_fraction H are left out; at f_m the
  // whole ungated half counts. So S(f)/S(f_m) = (tau0 - g)/(H - g).
  const double half = 0.5 * off_period_s;
  const double gate = square.gate_fraction * half;
  r.off_frequency_theory_ratio = (r.numbers.transit_time_s - gate) / (half - gate);
  std::size_t zero = 0;
  for (const double d : r.off_frequency.trace.modulation_rad) zero += std::abs(d) < 1e-9 ? 1 : 0;
  r.off_frequency_spike_fraction =
      r.off_frequency.trace.modulation_rad.empty()
          ? 0.0
          : static_cast<double>(zero) /
                static_cast<double>(r.off_frequency.trace.modulation_rad.size());
  return r;
}

}  // namespace foglab::sim
