// foglab — the FOG optical signal chain (optics.h).
#include "foglab/sim/optics.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <boost/math/special_functions/bessel.hpp>
#include <cmath>
#include <numbers>
#include <numeric>

#include "foglab/core/error.h"
#include "foglab/core/units.h"
#include "optics_internal.h"

namespace foglab::sim {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * kPi;
// Edges computed in floating point land within ~1e-12 of an integer; this
// keeps a sample exactly on an edge on the edge's far side.
constexpr double kEdgeEpsilon = 1e-9;

void check_positive(double v, const char* what) {
  if (!(v > 0.0) || !std::isfinite(v)) {
    throw UsageError(fmt::format("{} must be a positive finite number, got {}", what, v));
  }
}

// v in [low, high] (low excluded when `open_low`), else a UsageError.
void check_within(double v, double low, double high, const char* what, bool open_low = true) {
  const bool above = open_low ? v > low : v >= low;
  if (!(above && v <= high)) {
    throw UsageError(fmt::format("{} must be in {}{:g}, {:g}], got {}", what, open_low ? "(" : "[",
                                 low, high, v));
  }
}

/// The drive's half-period index at sample k (square: even = +pi/4).
std::int64_t half_index(double position) {
  return static_cast<std::int64_t>(std::floor(position + kEdgeEpsilon));
}

/// A rate profile's value at t inside segment i (time_s[i] <= t <= time_s[i + 1]).
double profile_segment_value(const RateInput& r, std::size_t i, double t) {
  const double w = (t - r.time_s[i]) / (r.time_s[i + 1] - r.time_s[i]);
  return r.profile_rad_s[i] + w * (r.profile_rad_s[i + 1] - r.profile_rad_s[i]);
}

/// The input rate at increasing times, without a search per sample.
class RateCursor {
 public:
  explicit RateCursor(const RateInput& r) : r_(r) {}
  double at(double t) {
    if (r_.kind != RateInput::Kind::profile) return r_.at(t);
    const auto& ts = r_.time_s;
    if (t <= ts.front()) return r_.profile_rad_s.front();
    if (t >= ts.back()) return r_.profile_rad_s.back();
    while (i_ + 1 < ts.size() && ts[i_ + 1] <= t) ++i_;
    return profile_segment_value(r_, i_, t);
  }

 private:
  const RateInput& r_;
  std::size_t i_ = 0;
};

/// The shared time simulation; `loop` null for the open loop.
OpticsResult run(const Coil& coil, const RateInput& rate, double duration_s, const OpticsOptions& o,
                 const ClosedLoopOptions* loop) {
  check_positive(duration_s, "the simulated duration [s]");
  if (o.samples_per_transit < 2) {
    throw UsageError(
        fmt::format("samples per transit time must be at least 2, got {}", o.samples_per_transit));
  }
  if (!(o.gate_fraction >= 0.0 && o.gate_fraction < 0.5)) {
    throw UsageError(fmt::format("the gate fraction must be in [0, 0.5), got {}", o.gate_fraction));
  }
  if (!(o.modulation_frequency_hz >= 0.0 &&
        o.modulation_frequency_hz <= kMaxModulationFrequencyHz)) {
    throw UsageError(
        fmt::format("the modulation frequency must be in [0, {:g}] Hz (0: the proper one), "
                    "got {}",
                    kMaxModulationFrequencyHz, o.modulation_frequency_hz));
  }
  check_positive(o.source_intensity, "the source intensity");
  check_positive(o.detector_gain, "the detector gain");
  check_positive(o.lowpass_periods, "the low-pass time constant [periods]");
  if (o.modulation == Modulation::sine) check_positive(o.sine_amplitude_rad, "the sine amplitude");
  if (loop && !(loop->loop_gain > 0.0 && loop->loop_gain < 2.0)) {
    throw UsageError(fmt::format("the loop gain must be in (0, 2), got {}", loop->loop_gain));
  }

  OpticsResult out;
  out.coil = coil_numbers(coil);
  const int m = o.samples_per_transit;
  const double tau0 = out.coil.transit_time_s;
  const double dt = tau0 / m;
  const double f = o.modulation_frequency_hz > 0.0 ? o.modulation_frequency_hz
                                                   : out.coil.modulation_frequency_hz;
  const Modulation modulation = loop ? Modulation::square : o.modulation;
  const double ks = out.coil.scale_factor_s;
  const double gamma = 0.5 * o.detector_gain * o.source_intensity;
  // The sine drive a sin(2 pi f t): its phase difference has the amplitude
  // 2 a sin(pi f tau0), which at f_m (f tau0 = 1/2) is 2 a.
  const double sine_drive_rad = 0.5 * o.sine_amplitude_rad;
  const double half_period_samples = 1.0 / (2.0 * f * dt);  // square: samples per half period
  const double samples_per_period = 2.0 * half_period_samples;
  const auto n = static_cast<std::int64_t>(std::llround(duration_s / dt));
  if (n < static_cast<std::int64_t>(std::ceil(samples_per_period))) {
    throw UsageError(
        fmt::format("the simulated duration {} s is shorter than one modulation period ({} s)",
                    duration_s, 1.0 / f));
  }
  out.sample_interval_s = dt;
  out.modulation_frequency_hz = f;
  out.samples = n;
  out.gamma = gamma;

  auto drive = [&](std::int64_t k) {
    switch (modulation) {
      case Modulation::square:
        return (half_index(static_cast<double>(k) / half_period_samples) % 2 == 0 ? 1.0 : -1.0) *
               (0.25 * kPi);
      case Modulation::sine:
        return sine_drive_rad * std::sin(kTwoPi * f * static_cast<double>(k) * dt);
      case Modulation::none:
        break;
    }
    return 0.0;
  };

  // The delay line: the modulator's phase one transit time ago, started with
  // the drive at negative times (the modulator ran before t = 0).
  std::vector<double> delay(static_cast<std::size_t>(m));
  for (int j = 0; j < m; ++j) delay[static_cast<std::size_t>(j)] = drive(j - m);

  RateCursor rate_at(rate);
  double psi = 0.0;  // closed loop: the staircase ramp [rad], in [0, 2 pi)
  double u = loop ? loop->initial_step_rad : 0.0;
  const double gain = loop ? loop->loop_gain : 0.0;
  const double alpha = 1.0 - std::exp(-1.0 / o.lowpass_periods);
  const double gate_samples = o.gate_fraction * half_period_samples;
  const bool trace = o.trace_stride > 0;

  std::int64_t period = 0;
  double sum_vr = 0.0, sum_rate = 0.0;
  std::int64_t used = 0, in_period = 0;
  bool filter_started = false;
  double filtered = 0.0;
  PeriodSeries& ps = out.periods;

  for (std::int64_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * dt;
    const double position = static_cast<double>(k) / samples_per_period;
    const std::int64_t p = half_index(position);
    if (p != period) {
      // The period ends: demodulate, filter, and (closed loop) update u.
      const double s = used > 0 ? 2.0 * sum_vr / static_cast<double>(used) : 0.0;
      const double demodulated =
          modulation == Modulation::none && used > 0 ? sum_vr / static_cast<double>(used) : s;
      ps.time_s.push_back(t);
      ps.rate_rad_s.push_back(sum_rate / static_cast<double>(in_period));
      if (loop) {
        const double e = demodulated / (2.0 * gamma);
        ps.demodulated.push_back(e);
        ps.output.push_back(-u / ks);
        ps.feedback_step_rad.push_back(u);
        ps.ramp_phase_rad.push_back(psi);
        u -= gain * e;
      } else {
        filtered = filter_started ? filtered + alpha * (demodulated - filtered) : demodulated;
        filter_started = true;
        ps.demodulated.push_back(demodulated);
        ps.output.push_back(filtered);
      }
      period = p;
      sum_vr = sum_rate = 0.0;
      used = in_period = 0;
    }
    // The staircase steps by u at every transit time.
    if (loop && k > 0 && k % m == 0) {
      psi = std::fmod(psi + u, kTwoPi);
      if (psi < 0.0) psi += kTwoPi;
    }

    const double omega = rate_at.at(t);
    const double phi_s = ks * omega;
    const double phase_now = drive(k) + psi;
    double& slot = delay[static_cast<std::size_t>(k % m)];
    const double dphi = phase_now - slot;
    slot = phase_now;
    const double v = gamma * (1.0 + std::cos(phi_s + dphi));

    double ref = 1.0;  // none: the mean
    if (modulation == Modulation::square) {
      const double in_half = static_cast<double>(k) / half_period_samples;
      const std::int64_t h = half_index(in_half);
      const bool gated =
          (in_half - static_cast<double>(h)) * half_period_samples + kEdgeEpsilon < gate_samples;
      ref = gated ? 0.0 : (h % 2 == 0 ? -1.0 : 1.0);
    } else if (modulation == Modulation::sine) {
      ref = -std::cos(kTwoPi * f * (t - 0.5 * tau0));
    }
    if (ref != 0.0) {
      sum_vr += v * ref;
      ++used;
    }
    sum_rate += omega;
    ++in_period;

    if (trace && k % o.trace_stride == 0 && out.trace.time_s.size() < o.trace_limit) {
      SampleTrace& tr = out.trace;
      tr.time_s.push_back(t);
      tr.rate_rad_s.push_back(omega);
      tr.sagnac_phase_rad.push_back(phi_s);
      tr.modulation_rad.push_back(dphi);
      tr.total_phase_rad.push_back(phi_s + dphi);
      tr.detector.push_back(v);
      tr.reference.push_back(ref);
      if (loop) tr.ramp_phase_rad.push_back(psi);
    }
  }
  return out;
}

SweepResult sweep(const Coil& coil, double range_rad_s, const OpticsOptions& options,
                  const ClosedLoopOptions* loop, const SweepOptions& s) {
  check_within(range_rad_s, 0.0, kMaxInputRateRadS, "the sweep range [rad/s]");
  if (s.settle_periods < 0 || s.average_periods < 1) {
    throw UsageError(
        fmt::format("sweep: settle periods must be >= 0 and average periods >= 1, "
                    "got {} and {}",
                    s.settle_periods, s.average_periods));
  }
  SweepResult r;
  r.closed_loop = loop != nullptr;
  r.rates_rad_s = lab_sweep_rates(range_rad_s);
  const CoilNumbers c = coil_numbers(coil);
  const double f = options.modulation_frequency_hz > 0.0 ? options.modulation_frequency_hz
                                                         : c.modulation_frequency_hz;
  for (const double rate : r.rates_rad_s) {
    double out = 0.0;
    double feedback_rad = -c.scale_factor_s * rate;
    if (s.method == SweepMethod::analytic) {
      out = loop ? rate : steady_state_output(coil, rate, options);
    } else {
      // The rate ramps up over the first half of the settling time and is
      // held for the second half, so the loop's ramp lag (a type-1 loop
      // lags a ramp) has died out (as (1 - g)^periods) before averaging.
      const double ramp_s = 0.5 * s.settle_periods / f;
      const double total_s = (s.settle_periods + s.average_periods + 1) / f;
      const RateInput input =
          s.settle_periods > 1 ? RateInput::ramp(0.0, rate, ramp_s) : RateInput::constant(rate);
      OpticsOptions o = options;
      o.trace_stride = 0;
      const OpticsResult sim = loop ? simulate_closed_loop(coil, input, total_s, o, *loop)
                                    : simulate_open_loop(coil, input, total_s, o);
      out = detail::mean_of_last(loop ? sim.periods.output : sim.periods.demodulated,
                                 static_cast<std::size_t>(s.average_periods));
      if (loop) {
        feedback_rad = detail::mean_of_last(sim.periods.feedback_step_rad,
                                            static_cast<std::size_t>(s.average_periods));
      }
    }
    if (loop) r.feedback_steps_rad.push_back(feedback_rad);
    r.outputs.push_back(out);
    r.scale_factors.push_back(out / rate);
  }
  r.nonlinearity_percent = nonlinearity_percent(r.rates_rad_s, r.outputs);
  return r;
}

}  // namespace

CoilNumbers coil_numbers(const Coil& coil) {
  check_within(coil.length_m, 0.0, kMaxFibreLengthM, "the fibre length [m]");
  check_within(coil.radius_m, 0.0, kMaxCoilRadiusM, "the coil radius [m]");
  check_within(coil.wavelength_m, kMinWavelengthM, kMaxWavelengthM, "the wavelength [m]", false);
  check_within(coil.group_index, 1.0, kMaxGroupIndex, "the group index", false);
  CoilNumbers n;
  n.scale_factor_s =
      4.0 * kPi * coil.radius_m * coil.length_m / (coil.wavelength_m * kSpeedOfLightM_S);
  n.omega_pi2_rad_s = 0.5 * kPi / n.scale_factor_s;
  n.omega_pi2_deg_s = n.omega_pi2_rad_s * kDegPerRad;
  n.transit_time_s = coil.group_index * coil.length_m / kSpeedOfLightM_S;
  n.modulation_frequency_hz = 1.0 / (2.0 * n.transit_time_s);
  return n;
}

Coil lab1_coil(int variant) {
  // Table 4: L [km], R [cm], lambda [nm].
  static constexpr std::array<std::array<double, 3>, kLab1Variants> kTable = {{
      {0.3, 4.0, 830.0},
      {0.5, 8.0, 830.0},
      {0.8, 10.0, 830.0},
      {2.0, 12.0, 1550.0},
      {2.0, 20.0, 1550.0},
      {5.0, 20.0, 1550.0},
  }};
  if (variant < 1 || variant > kLab1Variants) {
    throw UsageError(fmt::format("lab 1 variant {}: the manual's Table 4 has variants 1 to {}",
                                 variant, kLab1Variants));
  }
  const auto& row = kTable[static_cast<std::size_t>(variant - 1)];
  Coil c;
  c.length_m = row[0] * 1e3;
  c.radius_m = row[1] * 1e-2;
  c.wavelength_m = row[2] * 1e-9;
  return c;
}

std::string_view to_string(Modulation m) {
  switch (m) {
    case Modulation::none:
      return "none";
    case Modulation::square:
      return "square";
    case Modulation::sine:
      return "sine";
  }
  return "?";
}

Modulation modulation_from_string(std::string_view text) {
  for (const Modulation m : {Modulation::none, Modulation::square, Modulation::sine}) {
    if (text == to_string(m)) return m;
  }
  throw UsageError(fmt::format("modulation '{}': expected none, square or sine", text));
}

RateInput RateInput::constant(double rate_rad_s) {
  if (!(std::fabs(rate_rad_s) <= kMaxInputRateRadS)) {
    throw UsageError(
        fmt::format("the input rate must be finite and at most {:g} rad/s in "
                    "magnitude, got {}",
                    kMaxInputRateRadS, rate_rad_s));
  }
  RateInput r;
  r.rate_rad_s = rate_rad_s;
  return r;
}

RateInput RateInput::ramp(double start_rad_s, double end_rad_s, double duration_s) {
  if (!(std::fabs(start_rad_s) <= kMaxInputRateRadS && std::fabs(end_rad_s) <= kMaxInputRateRadS)) {
    throw UsageError(
        fmt::format("the ramp's rates must be finite and at most {:g} rad/s in "
                    "magnitude, got {} and {}",
                    kMaxInputRateRadS, start_rad_s, end_rad_s));
  }
  check_positive(duration_s, "the ramp duration [s]");
  RateInput r;
  r.kind = Kind::ramp;
  r.rate_rad_s = start_rad_s;
  r.end_rate_rad_s = end_rad_s;
  r.ramp_duration_s = duration_s;
  return r;
}

RateInput RateInput::profile(std::vector<double> time_s, std::vector<double> rate_rad_s) {
  if (time_s.empty() || time_s.size() != rate_rad_s.size()) {
    throw UsageError(
        fmt::format("a rate profile needs as many times as rates (at least one), got "
                    "{} and {}",
                    time_s.size(), rate_rad_s.size()));
  }
  for (std::size_t i = 0; i < time_s.size(); ++i) {
    if (!std::isfinite(time_s[i]) || !(std::fabs(rate_rad_s[i]) <= kMaxInputRateRadS)) {
      throw UsageError(
          fmt::format("rate profile point {}: the time must be finite and the rate "
                      "at most {:g} rad/s in magnitude, got {} s and {} rad/s",
                      i + 1, kMaxInputRateRadS, time_s[i], rate_rad_s[i]));
    }
    if (i > 0 && !(time_s[i] > time_s[i - 1])) {
      throw UsageError(fmt::format("rate profile point {}: times must increase ({} s after {} s)",
                                   i + 1, time_s[i], time_s[i - 1]));
    }
  }
  RateInput r;
  r.kind = Kind::profile;
  r.time_s = std::move(time_s);
  r.profile_rad_s = std::move(rate_rad_s);
  return r;
}

double RateInput::at(double t_s) const {
  switch (kind) {
    case Kind::constant:
      return rate_rad_s;
    case Kind::ramp:
      return t_s >= ramp_duration_s ? end_rate_rad_s
                                    : rate_rad_s + (end_rate_rad_s - rate_rad_s) *
                                                       std::max(0.0, t_s) / ramp_duration_s;
    case Kind::profile: {
      if (t_s <= time_s.front()) return profile_rad_s.front();
      if (t_s >= time_s.back()) return profile_rad_s.back();
      const auto it = std::upper_bound(time_s.begin(), time_s.end(), t_s);
      return profile_segment_value(*this, static_cast<std::size_t>(it - time_s.begin()) - 1, t_s);
    }
  }
  return 0.0;
}

OpticsResult simulate_open_loop(const Coil& coil, const RateInput& rate, double duration_s,
                                const OpticsOptions& options) {
  return run(coil, rate, duration_s, options, nullptr);
}

OpticsResult simulate_closed_loop(const Coil& coil, const RateInput& rate, double duration_s,
                                  const OpticsOptions& options, const ClosedLoopOptions& loop) {
  return run(coil, rate, duration_s, options, &loop);
}

double steady_state_output(const Coil& coil, double rate_rad_s, const OpticsOptions& o) {
  const CoilNumbers c = coil_numbers(coil);
  const double f =
      o.modulation_frequency_hz > 0.0 ? o.modulation_frequency_hz : c.modulation_frequency_hz;
  const double gamma = 0.5 * o.detector_gain * o.source_intensity;
  const double phi_s = c.scale_factor_s * rate_rad_s;
  switch (o.modulation) {
    case Modulation::none:
      return gamma * (1.0 + std::cos(phi_s));
    case Modulation::square: {
      // The fraction of time the drive and its delayed copy differ: a
      // triangle in f tau0, 1 at f_m.
      const double x = std::fmod(f * c.transit_time_s, 1.0);
      const double differ = x <= 0.5 ? 2.0 * x : 2.0 - 2.0 * x;
      return 2.0 * gamma * differ * std::sin(phi_s);
    }
    case Modulation::sine: {
      const double amplitude = o.sine_amplitude_rad * std::sin(kPi * f * c.transit_time_s);
      return 2.0 * gamma * boost::math::cyl_bessel_j(1, amplitude) * std::sin(phi_s);
    }
  }
  return 0.0;
}

std::vector<double> lab_sweep_rates(double range) {
  std::vector<double> rates;
  for (int k = -5; k <= 5; ++k) {
    if (k != 0) rates.push_back(range * k / 5.0);
  }
  return rates;
}

double nonlinearity_percent(std::span<const double> rates, std::span<const double> outputs) {
  if (rates.empty() || rates.size() != outputs.size()) {
    throw UsageError(
        fmt::format("nonlinearity: need as many outputs as rates (at least one), got "
                    "{} and {}",
                    outputs.size(), rates.size()));
  }
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, sum = 0.0;
  for (std::size_t i = 0; i < rates.size(); ++i) {
    if (rates[i] == 0.0) throw UsageError("nonlinearity: a rate of zero has no scale factor");
    const double sf = outputs[i] / rates[i];
    lo = std::min(lo, sf);
    hi = std::max(hi, sf);
    sum += sf;
  }
  const double mean = sum / static_cast<double>(rates.size());
  return 100.0 * (hi - lo) / std::abs(mean);
}

SweepResult sweep_open_loop(const Coil& coil, double range_rad_s, const OpticsOptions& options,
                            const SweepOptions& sweep_options) {
  return sweep(coil, range_rad_s, options, nullptr, sweep_options);
}

SweepResult sweep_closed_loop(const Coil& coil, double range_rad_s, const OpticsOptions& options,
                              const ClosedLoopOptions& loop, const SweepOptions& sweep_options) {
  return sweep(coil, range_rad_s, options, &loop, sweep_options);
}

SweepResult feedback_phase_form(const SweepResult& closed_loop) {
  if (!closed_loop.closed_loop ||
      closed_loop.feedback_steps_rad.size() != closed_loop.rates_rad_s.size()) {
    throw UsageError(
        "the feedback phase form is the closed loop's: an open-loop sweep has no feedback phase");
  }
  if (closed_loop.phase_form) return closed_loop;
  SweepResult r = closed_loop;
  r.phase_form = true;
  r.outputs = closed_loop.feedback_steps_rad;
  r.scale_factors.clear();
  for (std::size_t i = 0; i < r.rates_rad_s.size(); ++i) {
    r.scale_factors.push_back(r.outputs[i] / r.rates_rad_s[i]);
  }
  r.nonlinearity_percent = nonlinearity_percent(r.rates_rad_s, r.outputs);
  return r;
}

std::optional<double> range_for_nonlinearity(const Coil& coil, double target_percent,
                                             const OpticsOptions& options,
                                             const SweepOptions& sweep_options,
                                             double relative_tolerance) {
  check_positive(target_percent, "the target nonlinearity [%]");
  check_positive(relative_tolerance, "the relative tolerance");
  const double top = coil_numbers(coil).omega_pi2_rad_s;
  auto nl = [&](double range) {
    return sweep_open_loop(coil, range, options, sweep_options).nonlinearity_percent;
  };
  if (nl(top) < target_percent) return std::nullopt;
  double lo = 0.0, hi = top;
  while (hi - lo > relative_tolerance * hi) {
    const double mid = 0.5 * (lo + hi);
    (nl(mid) < target_percent ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace foglab::sim
