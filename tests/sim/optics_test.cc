// The FOG optical signal chain (sim/optics.h) against theory: the coil's
// numbers (manual formulas (1), (9)), the time simulation against the
// analytic steady state, the closed loop's linearity, off-frequency
// modulation, and the lab's sweep procedure.
//
// The closed forms are computed here independently of optics.cc: K_s from
// the coil's geometry, J1 from std::cyl_bessel_j (optics.cc uses Boost), the
// ten-rate nonlinearity of sin and its 30 % root by our own bisection.
#include "foglab/sim/optics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/core/units.h"

namespace foglab::sim {
namespace {

constexpr double kPi = std::numbers::pi;

constexpr double kC = 299792458.0;

/// K_s = 4 pi R L / (lambda c), from the geometry alone.
double scale_factor(const Coil& c) {
  return 4.0 * kPi * c.radius_m * c.length_m / (c.wavelength_m * kC);
}
/// Omega_pi/2 = (pi/2) / K_s.
double omega_pi2(const Coil& c) { return 0.5 * kPi / scale_factor(c); }
/// tau0 = n_g L / c.
double transit(const Coil& c) { return c.group_index * c.length_m / kC; }
/// f_m = 1 / (2 tau0).
double proper_frequency(const Coil& c) { return 1.0 / (2.0 * transit(c)); }

double sinc(double x) { return x == 0.0 ? 1.0 : std::sin(x) / x; }

/// The lab's ten-rate nonlinearity [%] of an output proportional to sin(K_s
/// Omega) over +-range, a = K_s range: the scale factors are proportional to
/// sinc(k a / 5), k = +-1..+-5 (even), largest at k = 1, smallest at k = 5.
double sin_nonlinearity_percent(double a) {
  double mean = 0.0;
  for (int k = 1; k <= 5; ++k) mean += sinc(k * a / 5.0);
  mean /= 5.0;
  return 100.0 * (sinc(a / 5.0) - sinc(a)) / mean;
}

/// Rates spanning +-1.5 Omega_pi/2 (in units of Omega_pi/2).
const std::vector<double> kRateFractions = {-1.5, -1.2, -1.0, -0.7, -0.5, -0.2, 0.0,
                                            0.1,  0.35, 0.5,  0.8,  1.0,  1.3,  1.5};

/// Every period's demodulated value and the low-pass output agree with
/// `expected` within `tolerance`; returns the number of periods checked.
std::size_t expect_steady(const OpticsResult& r, double expected, double tolerance,
                          const std::string& what) {
  EXPECT_GE(r.periods.demodulated.size(), 10u) << what;
  for (std::size_t i = 0; i < r.periods.demodulated.size(); ++i) {
    EXPECT_NEAR(r.periods.demodulated[i], expected, tolerance) << what << ", period " << i;
    EXPECT_NEAR(r.periods.output[i], expected, tolerance) << what << ", low-passed, period " << i;
  }
  return r.periods.demodulated.size();
}

// --- the coil -------------------------------------------------------------------

TEST(Coil, Table4Variant1HasTheManualsNumbers) {
  // L = 0.3 km, R = 4 cm, lambda = 830 nm: K_s = 4 pi R L / (lambda c).
  const CoilNumbers n = coil_numbers(lab1_coil(1));
  const double ks = 4.0 * kPi * 0.04 * 300.0 / (830e-9 * 299792458.0);
  EXPECT_NEAR(n.scale_factor_s, ks, 1e-12 * ks);
  EXPECT_NEAR(n.scale_factor_s, 0.60603, 1e-5);
  EXPECT_NEAR(n.omega_pi2_rad_s, (kPi / 2.0) / ks, 1e-12);
  EXPECT_NEAR(n.omega_pi2_deg_s, 148.51, 0.01);
  EXPECT_NEAR(n.transit_time_s, 300.0 / 299792458.0, 1e-18);
  EXPECT_NEAR(n.modulation_frequency_hz, 299792458.0 / 600.0, 1e-6);
}

TEST(Coil, EveryVariantsNumbersFollowFormulas1And9) {
  for (int v = 1; v <= kLab1Variants; ++v) {
    const Coil c = lab1_coil(v);
    const CoilNumbers n = coil_numbers(c);
    EXPECT_NEAR(n.scale_factor_s, scale_factor(c), 1e-12 * scale_factor(c)) << "variant " << v;
    EXPECT_NEAR(n.omega_pi2_rad_s, omega_pi2(c), 1e-12 * omega_pi2(c)) << "variant " << v;
    EXPECT_NEAR(n.omega_pi2_deg_s, omega_pi2(c) * 180.0 / kPi, 1e-10 * n.omega_pi2_deg_s);
    EXPECT_NEAR(n.modulation_frequency_hz, proper_frequency(c), 1e-9 * proper_frequency(c));
  }
}

// --- 1. the time simulation against the analytic steady state ------------------

TEST(OpenLoop, SquareModulationFollowsSinOfSagnacPhase) {
  for (const int v : {1, 4, 6}) {
    const Coil c = lab1_coil(v);
    OpticsOptions o;
    o.modulation = Modulation::square;
    o.source_intensity = 2.0;
    o.detector_gain = 1.5;  // gamma = 1.5
    const double gamma = 1.5;
    const double full_scale = 2.0 * gamma;
    const double duration = 40.0 / proper_frequency(c);
    for (const double x : kRateFractions) {
      const double rate = x * omega_pi2(c);
      const double expected = 2.0 * gamma * std::sin(scale_factor(c) * rate);
      const std::string what = "variant " + std::to_string(v) + ", rate " + std::to_string(x);
      EXPECT_NEAR(steady_state_output(c, rate, o), expected, 1e-12) << what;
      const OpticsResult r = simulate_open_loop(c, RateInput::constant(rate), duration, o);
      EXPECT_DOUBLE_EQ(r.gamma, gamma);
      EXPECT_NEAR(r.modulation_frequency_hz, proper_frequency(c), 1e-9 * proper_frequency(c));
      EXPECT_EQ(expect_steady(r, expected, 1e-3 * full_scale, what), 39u) << what;
    }
  }
}

TEST(OpenLoop, SineModulationFollowsJ1TimesSinOfSagnacPhase) {
  for (const int v : {1, 4, 6}) {
    const Coil c = lab1_coil(v);
    for (const double phi_m : {1.8, 1.0}) {
      OpticsOptions o;
      o.modulation = Modulation::sine;
      o.sine_amplitude_rad = phi_m;
      const double gamma = 0.5;
      const double j1 = std::cyl_bessel_j(1.0, phi_m);
      const double full_scale = 2.0 * gamma * j1;
      const double duration = 40.0 / proper_frequency(c);
      for (const double x : kRateFractions) {
        const double rate = x * omega_pi2(c);
        const double expected = 2.0 * gamma * j1 * std::sin(scale_factor(c) * rate);
        const std::string what = "variant " + std::to_string(v) + ", phi_m " +
                                 std::to_string(phi_m) + ", rate " + std::to_string(x);
        EXPECT_NEAR(steady_state_output(c, rate, o), expected, 1e-12) << what;
        const OpticsResult r = simulate_open_loop(c, RateInput::constant(rate), duration, o);
        expect_steady(r, expected, 1e-3 * full_scale, what);
      }
    }
  }
  // Formula (8)'s default amplitude sits near J1's maximum 0.58.
  EXPECT_NEAR(std::cyl_bessel_j(1.0, 1.8), 0.5815, 1e-4);
}

TEST(OpenLoop, NoModulationGivesMeanDetectorGammaOnePlusCos) {
  for (const int v : {1, 4, 6}) {
    const Coil c = lab1_coil(v);
    OpticsOptions o;
    o.modulation = Modulation::none;
    o.source_intensity = 3.0;  // gamma = 1.5
    const double gamma = 1.5;
    const double duration = 20.0 / proper_frequency(c);
    for (const double x : kRateFractions) {
      const double rate = x * omega_pi2(c);
      const double expected = gamma * (1.0 + std::cos(scale_factor(c) * rate));
      const std::string what = "variant " + std::to_string(v) + ", rate " + std::to_string(x);
      EXPECT_NEAR(steady_state_output(c, rate, o), expected, 1e-12) << what;
      const OpticsResult r = simulate_open_loop(c, RateInput::constant(rate), duration, o);
      expect_steady(r, expected, 1e-3 * 2.0 * gamma, what);
    }
  }
}

// --- 2. the closed loop --------------------------------------------------------------

TEST(ClosedLoop, SweepOverThreeOmegaPi2IsLinearWithin10Ppm) {
  for (const int v : {1, 4, 6}) {
    const Coil c = lab1_coil(v);
    const double range = 3.0 * omega_pi2(c);
    const SweepResult s = sweep_closed_loop(c, range);
    EXPECT_TRUE(s.closed_loop);
    ASSERT_EQ(s.outputs.size(), 10u);
    EXPECT_LT(s.nonlinearity_percent, 1e-3) << "variant " << v;  // 10 ppm
    for (std::size_t i = 0; i < s.outputs.size(); ++i) {
      EXPECT_NEAR(s.outputs[i], s.rates_rad_s[i], 1e-5 * range)
          << "variant " << v << ", rate " << s.rates_rad_s[i];
      EXPECT_NEAR(s.scale_factors[i], 1.0, 1e-5) << "variant " << v;
    }
  }
}

TEST(ClosedLoop, FollowsRampBeyondOmegaPi2WithLagOfPhaseStepOverGain) {
  const Coil c = lab1_coil(1);
  const double f = proper_frequency(c);
  const double top = 4.0 * omega_pi2(c);  // phi_s up to 2 pi
  const int ramp_periods = 300, hold_periods = 100;
  const RateInput ramp = RateInput::ramp(0.0, top, ramp_periods / f);
  for (const double gain : {0.5, 0.25}) {
    ClosedLoopOptions loop;
    loop.loop_gain = gain;
    const OpticsResult r =
        simulate_closed_loop(c, ramp, (ramp_periods + hold_periods + 1) / f, {}, loop);
    const PeriodSeries& p = r.periods;
    ASSERT_GE(p.output.size(), static_cast<std::size_t>(ramp_periods + hold_periods));
    ASSERT_EQ(p.feedback_step_rad.size(), p.output.size());
    // The lag: (phase change per period) / gain / K_s = (rate change per period) / gain.
    const double lag = (top / ramp_periods) / gain;
    for (int i = 30; i < ramp_periods - 1; ++i) {
      const auto k = static_cast<std::size_t>(i);
      EXPECT_NEAR(p.rate_rad_s[k] - p.output[k], lag, 0.2 * lag)
          << "gain " << gain << ", period " << i;
      EXPECT_GT(p.output[k], p.output[k - 1]) << "no fold: period " << i;
      EXPECT_NEAR(p.output[k], -p.feedback_step_rad[k] / scale_factor(c), 1e-9 * top);
    }
    // Held: it settles to the final rate.
    for (std::size_t k = p.output.size() - 50; k < p.output.size(); ++k) {
      EXPECT_NEAR(p.output[k], top, 1e-5 * top) << "gain " << gain << ", period " << k;
      EXPECT_NEAR(p.demodulated[k], 0.0, 1e-5) << "the error e = sin(phi_s + u) is nulled";
    }
  }
}

TEST(ClosedLoop, TheFeedbackPhaseIsAStaircaseResetBy2Pi) {
  // The manual's Fig. 11: the phase ramp psi steps by u every transit time
  // (two steps a period at the proper frequency) and is reset by 2 pi
  // whenever it leaves [0, 2 pi); at a constant rate u settles to -phi_s,
  // so psi resets about every pi / |phi_s| periods.
  const Coil c = lab1_coil(3);
  const double f = proper_frequency(c);
  const double rate = 0.3 * omega_pi2(c);  // phi_s = 0.15 pi
  ClosedLoopOptions loop;
  OpticsOptions every_sample;
  every_sample.trace_stride = 1;
  every_sample.trace_limit = 1000000;
  const OpticsResult r =
      simulate_closed_loop(c, RateInput::constant(rate), 400 / f, every_sample, loop);
  const PeriodSeries& p = r.periods;
  ASSERT_EQ(p.ramp_phase_rad.size(), p.output.size());
  // Sample by sample: psi changes only where a transit time begins.
  const std::vector<double>& psi_k = r.trace.ramp_phase_rad;
  ASSERT_EQ(psi_k.size(), r.trace.time_s.size());
  const int m = every_sample.samples_per_transit;
  int steps = 0;
  for (std::size_t k = 1; k < psi_k.size(); ++k) {
    if (psi_k[k] != psi_k[k - 1]) {
      EXPECT_EQ(k % static_cast<std::size_t>(m), 0u) << "sample " << k;
      ++steps;
    }
  }
  EXPECT_GE(steps, 700);  // two a period over 400 periods, once u has moved
  int resets = 0;
  for (std::size_t k = 1; k < p.ramp_phase_rad.size(); ++k) {
    const double psi = p.ramp_phase_rad[k], before = p.ramp_phase_rad[k - 1];
    EXPECT_GE(psi, 0.0);
    EXPECT_LT(psi, 2.0 * kPi);
    // Two steps of this period's u, wrapped into [0, 2 pi).
    const double step = std::remainder(psi - before - 2.0 * p.feedback_step_rad[k], 2.0 * kPi);
    EXPECT_NEAR(step, 0.0, 1e-9) << "period " << k;
    resets += std::fabs(psi - before) > kPi;
  }
  // u -> -phi_s = -0.15 pi: psi falls 0.3 pi a period, a reset every 6.7 periods.
  const double expected = 0.3 * kPi * static_cast<double>(p.ramp_phase_rad.size() - 1) / (2 * kPi);
  EXPECT_NEAR(resets, expected, 0.05 * expected + 2.0);
}

TEST(OpenLoop, RampOutputFoldsAfterOmegaPi2) {
  const Coil c = lab1_coil(1);
  const double f = proper_frequency(c);
  const double top = 3.0 * omega_pi2(c);
  const int ramp_periods = 300;
  const OpticsResult r =
      simulate_open_loop(c, RateInput::ramp(0.0, top, ramp_periods / f), (ramp_periods + 1) / f);
  const PeriodSeries& p = r.periods;
  ASSERT_GE(p.demodulated.size(), static_cast<std::size_t>(ramp_periods));
  const auto peak = std::max_element(p.demodulated.begin(), p.demodulated.end());
  const auto ipeak = static_cast<std::size_t>(peak - p.demodulated.begin());
  // The peak is the full scale 2 gamma, near Omega_pi/2 (one period's ramp step is 1 %).
  EXPECT_NEAR(*peak, 2.0 * r.gamma, 1e-3 * 2.0 * r.gamma);
  EXPECT_NEAR(p.rate_rad_s[ipeak], omega_pi2(c), 0.02 * omega_pi2(c));
  // Not monotonic: after the peak the output decreases, to -2 gamma at 3 Omega_pi/2.
  for (std::size_t k = ipeak + 2; k < p.demodulated.size(); ++k) {
    EXPECT_LT(p.demodulated[k], p.demodulated[k - 1]) << "period " << k;
  }
  EXPECT_LT(p.demodulated.back(), -0.99 * 2.0 * r.gamma);
}

// --- 3. off the proper frequency -------------------------------------------------------

TEST(OpenLoopOffFrequency, SquareAtHalfProperFrequencyWithoutGatingHalvesTheSignal) {
  for (const int v : {1, 6}) {
    const Coil c = lab1_coil(v);
    OpticsOptions o;
    o.modulation_frequency_hz = proper_frequency(c) / 2.0;
    o.gate_fraction = 0.0;
    const double ratio = 2.0 * o.modulation_frequency_hz * transit(c);  // 2 f tau0
    ASSERT_NEAR(ratio, 0.5, 1e-12);
    const double duration = 20.0 / o.modulation_frequency_hz;
    for (const double x : kRateFractions) {
      const double rate = x * omega_pi2(c);
      const double proper = 2.0 * 0.5 * std::sin(scale_factor(c) * rate);
      EXPECT_NEAR(steady_state_output(c, rate, o), ratio * proper, 1e-12);
      const OpticsResult r = simulate_open_loop(c, RateInput::constant(rate), duration, o);
      EXPECT_NEAR(r.modulation_frequency_hz, o.modulation_frequency_hz, 1e-6);
      expect_steady(r, steady_state_output(c, rate, o), 1e-3 * 2.0 * 0.5,
                    "variant " + std::to_string(v) + ", rate " + std::to_string(x));
    }
  }
}

TEST(OpenLoopOffFrequency, SquareWithGatingFallsByTau0MinusGateOverHalfPeriodMinusGate) {
  // At f_m / 2 with M = 8 a half period H = 2 tau0 is 16 samples: the
  // default gate H/8 is 2 of them (ratio 3/7) and H/4 is 4 (ratio 1/3). A
  // gate that is not a whole number of samples leaves out every sample that
  // starts inside it: 0.3 H = 4.8 samples gates 5, g = 5 dt.
  const Coil c = lab1_coil(1);
  for (const double gate : {0.125, 0.25, 0.3}) {
    OpticsOptions o;
    o.modulation_frequency_hz = proper_frequency(c) / 2.0;
    o.gate_fraction = gate;
    const double half = 1.0 / (2.0 * o.modulation_frequency_hz);  // H = 2 tau0
    const double dt = transit(c) / o.samples_per_transit;
    const double g = std::ceil(gate * half / dt - 1e-9) * dt;  // whole samples
    const double ratio = (transit(c) - g) / (half - g);
    if (gate == 0.125) {
      EXPECT_NEAR(ratio, 3.0 / 7.0, 1e-12);
    } else if (gate == 0.25) {
      EXPECT_NEAR(ratio, 1.0 / 3.0, 1e-12);
    } else {
      EXPECT_NEAR(ratio, 3.0 / 11.0, 1e-12);
    }
    const double duration = 20.0 / o.modulation_frequency_hz;
    for (const double x : kRateFractions) {
      const double rate = x * omega_pi2(c);
      const double expected = ratio * 2.0 * 0.5 * std::sin(scale_factor(c) * rate);
      const OpticsResult r = simulate_open_loop(c, RateInput::constant(rate), duration, o);
      expect_steady(r, expected, 1e-3 * 2.0 * 0.5,
                    "gate " + std::to_string(gate) + ", rate " + std::to_string(x));
    }
  }
  // At the proper frequency the gate costs nothing: the signal stays 2 gamma sin(phi_s).
  OpticsOptions o;
  o.gate_fraction = 0.3;
  const double rate = 0.4 * omega_pi2(c);
  const OpticsResult r =
      simulate_open_loop(c, RateInput::constant(rate), 20.0 / proper_frequency(c), o);
  expect_steady(r, std::sin(scale_factor(c) * rate), 1e-3, "proper frequency, gate 0.3");
}

/// The fraction of samples (over whole periods) whose modulation phase
/// difference is 0; checks the detector at every sample.
double zero_difference_fraction(const Coil& c, double rate, const OpticsOptions& o) {
  const double f =
      o.modulation_frequency_hz > 0.0 ? o.modulation_frequency_hz : proper_frequency(c);
  const OpticsResult r = simulate_open_loop(c, RateInput::constant(rate), 10.0 / f, o);
  const SampleTrace& t = r.trace;
  const auto per_period = static_cast<std::size_t>(std::llround(1.0 / (f * r.sample_interval_s)));
  const std::size_t n = t.modulation_rad.size() / per_period * per_period;
  EXPECT_GE(n, 9 * per_period);
  const double phi_s = scale_factor(c) * rate;
  std::size_t zeros = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double d = t.modulation_rad[k];
    EXPECT_NEAR(t.sagnac_phase_rad[k], phi_s, 1e-12);
    EXPECT_NEAR(t.total_phase_rad[k], phi_s + d, 1e-12);
    if (std::abs(d) < 1e-12) {
      ++zeros;
      // The transition spike: both waves have the same drive phase.
      EXPECT_NEAR(t.detector[k], r.gamma * (1.0 + std::cos(phi_s)), 1e-12) << "sample " << k;
    } else {
      EXPECT_NEAR(std::abs(d), kPi / 2.0, 1e-12) << "sample " << k;
      EXPECT_NEAR(t.detector[k], r.gamma * (1.0 - (d > 0 ? 1.0 : -1.0) * std::sin(phi_s)), 1e-12);
    }
  }
  return static_cast<double>(zeros) / static_cast<double>(n);
}

TEST(OpenLoopOffFrequency, HalfFrequencySpendsOneMinus2FTau0OfTheTimeAtZeroPhaseDifference) {
  const Coil c = lab1_coil(2);
  OpticsOptions o;
  o.trace_stride = 1;
  o.modulation_frequency_hz = proper_frequency(c) / 2.0;
  const double rate = 0.3 * omega_pi2(c);
  const double expected = 1.0 - 2.0 * o.modulation_frequency_hz * transit(c);  // 1 - 2 f tau0
  ASSERT_NEAR(expected, 0.5, 1e-12);
  EXPECT_NEAR(zero_difference_fraction(c, rate, o), expected, 1e-12);
  o.modulation_frequency_hz = 0.0;  // f_m: every sample at +-pi/2
  EXPECT_EQ(zero_difference_fraction(c, rate, o), 0.0);
}

TEST(OpenLoopOffFrequency, SineAtHalfFrequencyHasAmplitudePhiMSinPiF0Tau0) {
  for (const int v : {1, 6}) {
    const Coil c = lab1_coil(v);
    OpticsOptions o;
    o.modulation = Modulation::sine;
    o.modulation_frequency_hz = proper_frequency(c) / 2.0;
    const double j1 = std::cyl_bessel_j(1.0, 1.8 * std::sin(kPi / 4.0));
    const double duration = 20.0 / o.modulation_frequency_hz;
    for (const double x : kRateFractions) {
      const double rate = x * omega_pi2(c);
      const double expected = 2.0 * 0.5 * j1 * std::sin(scale_factor(c) * rate);
      EXPECT_NEAR(steady_state_output(c, rate, o), expected, 1e-12);
      const OpticsResult r = simulate_open_loop(c, RateInput::constant(rate), duration, o);
      expect_steady(r, expected, 1e-3 * 2.0 * 0.5 * std::cyl_bessel_j(1.0, 1.8),
                    "variant " + std::to_string(v) + ", rate " + std::to_string(x));
    }
  }
}

// --- 4. the lab's procedures ----------------------------------------------------------

TEST(Sweep, LabRatesAreTenStepsOfRangeOverFiveWithoutZero) {
  const double range = 2.5;
  const std::vector<double> r = lab_sweep_rates(range);
  ASSERT_EQ(r.size(), 10u);
  std::size_t i = 0;
  for (int k = -5; k <= 5; ++k) {
    if (k == 0) continue;
    EXPECT_NEAR(r[i++], range * k / 5.0, 1e-15) << "k = " << k;
  }
  EXPECT_EQ(std::count(r.begin(), r.end(), 0.0), 0);
}

TEST(Sweep, NonlinearityPercentIsMaxMinusMinOverMeanScaleFactor) {
  const std::vector<double> rates = {-2.0, -1.0, 1.0, 2.0};
  const std::vector<double> out = {-4.0, -2.2, 2.0, 4.4};  // SF 2, 2.2, 2, 2.2
  EXPECT_NEAR(nonlinearity_percent(rates, out), 100.0 * 0.2 / 2.1, 1e-12);
  EXPECT_THROW(nonlinearity_percent(rates, std::vector<double>{1.0}), UsageError);
  EXPECT_THROW(nonlinearity_percent(std::vector<double>{0.0, 1.0}, std::vector<double>{1.0, 1.0}),
               UsageError);
  EXPECT_THROW(nonlinearity_percent(std::vector<double>{}, std::vector<double>{}), UsageError);
}

TEST(Sweep, OpenLoopNonlinearityOverOmegaPi2Is41_60PercentBothMethods) {
  const double expected = sin_nonlinearity_percent(kPi / 2.0);
  EXPECT_NEAR(expected, 41.60, 0.005);
  SweepOptions analytic;
  analytic.method = SweepMethod::analytic;
  for (const int v : {1, 4, 6}) {
    const Coil c = lab1_coil(v);
    const SweepResult a = sweep_open_loop(c, omega_pi2(c), {}, analytic);
    const SweepResult t = sweep_open_loop(c, omega_pi2(c));
    EXPECT_FALSE(t.closed_loop);
    EXPECT_NEAR(a.nonlinearity_percent, expected, 1e-9) << "variant " << v;
    EXPECT_NEAR(t.nonlinearity_percent, a.nonlinearity_percent, 0.01) << "variant " << v;
    ASSERT_EQ(t.outputs.size(), 10u);
    for (std::size_t i = 0; i < 10; ++i) {
      EXPECT_NEAR(t.outputs[i], std::sin(scale_factor(c) * t.rates_rad_s[i]), 1e-3);
      EXPECT_NEAR(t.scale_factors[i], t.outputs[i] / t.rates_rad_s[i],
                  1e-15 * std::abs(t.scale_factors[i]));
    }
  }
}

TEST(Sweep, RangeFor30PercentNonlinearityIsTheSincRootForEveryVariant) {
  // a = K_s range solves sin_nonlinearity_percent(a) = 30 on (0, pi/2]
  // (increasing there); our own bisection.
  double lo = 1e-6, hi = kPi / 2.0;
  ASSERT_LT(sin_nonlinearity_percent(lo), 30.0);
  ASSERT_GT(sin_nonlinearity_percent(hi), 30.0);
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (sin_nonlinearity_percent(mid) < 30.0 ? lo : hi) = mid;
  }
  const double root = 0.5 * (lo + hi);  // in units of phi_s
  double first_relative = 0.0;
  for (int v = 1; v <= kLab1Variants; ++v) {
    const Coil c = lab1_coil(v);
    const std::optional<double> r = range_for_nonlinearity(c, 30.0);
    ASSERT_TRUE(r.has_value()) << "variant " << v;
    const double expected = root / scale_factor(c);
    EXPECT_NEAR(*r, expected, 1e-3 * expected) << "variant " << v;
    const double relative = *r / omega_pi2(c);
    if (v == 1) first_relative = relative;
    EXPECT_NEAR(relative, first_relative, 1e-3 * first_relative) << "variant " << v;
  }
  // 41.6 % is the most the open loop reaches within Omega_pi/2.
  EXPECT_FALSE(range_for_nonlinearity(lab1_coil(1), 45.0).has_value());
}

TEST(Sweep, ClosedLoopNonlinearityOverOmegaPi2IsBelow10Ppm) {
  for (const int v : {1, 6}) {
    const Coil c = lab1_coil(v);
    const SweepResult s = sweep_closed_loop(c, omega_pi2(c));
    EXPECT_TRUE(s.closed_loop);
    EXPECT_LT(s.nonlinearity_percent, 1e-3) << "variant " << v;
    SweepOptions analytic;
    analytic.method = SweepMethod::analytic;
    EXPECT_NEAR(sweep_closed_loop(c, omega_pi2(c), {}, {}, analytic).nonlinearity_percent, 0.0,
                1e-9);
  }
}

TEST(Sweep, TheManualsFormOfTheClosedLoopIsTheFeedbackPhaseWithScaleFactorMinusKs) {
  // Items 5.2-5.4 read the feedback phase step u: its scale factor u / Omega is -K_s (the
  // manual's -4.040 s for variant 3), and the nonlinearity is the rate form's (the factor
  // cancels). The phase is averaged from the simulated u, not converted from the output.
  const Coil c = lab1_coil(3);
  const double ks = scale_factor(c);
  EXPECT_NEAR(-ks, -4.040, 5e-4);
  const SweepResult rate = sweep_closed_loop(c, omega_pi2(c));
  ASSERT_EQ(rate.feedback_steps_rad.size(), rate.rates_rad_s.size());
  const SweepResult phase = feedback_phase_form(rate);
  EXPECT_TRUE(phase.phase_form);
  for (std::size_t i = 0; i < phase.rates_rad_s.size(); ++i) {
    EXPECT_NEAR(phase.outputs[i], -ks * rate.rates_rad_s[i], 1e-6 * ks * omega_pi2(c)) << i;
    EXPECT_NEAR(phase.scale_factors[i], -ks, 1e-6 * ks) << i;
    EXPECT_NEAR(phase.outputs[i], -ks * rate.outputs[i], 1e-12 * ks * omega_pi2(c)) << i;
  }
  EXPECT_NEAR(phase.nonlinearity_percent, rate.nonlinearity_percent, 1e-10);
  // The analytic sweep's phase is -K_s Omega exactly.
  SweepOptions analytic;
  analytic.method = SweepMethod::analytic;
  const SweepResult a = feedback_phase_form(sweep_closed_loop(c, omega_pi2(c), {}, {}, analytic));
  for (const double sf : a.scale_factors) EXPECT_NEAR(sf, -ks, 1e-12 * ks);
  // The open loop has no feedback phase.
  EXPECT_THROW(feedback_phase_form(sweep_open_loop(c, omega_pi2(c))), UsageError);
}

// --- 5. bad options and rate inputs ----------------------------------------------------

TEST(Optics, BadOptionsThrowUsageError) {
  const Coil good = lab1_coil(1);
  const double period = 1.0 / proper_frequency(good);
  const RateInput zero = RateInput::constant(0.0);
  Coil bad = good;
  bad.length_m = -300.0;
  EXPECT_THROW(coil_numbers(bad), UsageError);
  EXPECT_THROW(simulate_open_loop(bad, zero, 10 * period), UsageError);
  OpticsOptions o;
  o.samples_per_transit = 1;
  EXPECT_THROW(simulate_open_loop(good, zero, 10 * period, o), UsageError);
  o = {};
  o.gate_fraction = 0.6;
  EXPECT_THROW(simulate_open_loop(good, zero, 10 * period, o), UsageError);
  ClosedLoopOptions loop;
  loop.loop_gain = 2.5;
  EXPECT_THROW(simulate_closed_loop(good, zero, 10 * period, {}, loop), UsageError);
  EXPECT_THROW(simulate_open_loop(good, zero, 0.5 * period), UsageError);
  EXPECT_THROW(simulate_closed_loop(good, zero, 0.5 * period), UsageError);
  EXPECT_THROW(simulate_open_loop(good, zero, -1.0), UsageError);
  EXPECT_THROW(lab1_coil(7), UsageError);
  EXPECT_THROW(lab1_coil(0), UsageError);
  EXPECT_THROW(modulation_from_string("triangle"), UsageError);
  EXPECT_THROW(RateInput::profile({0.0, 2.0, 1.0}, {0.0, 1.0, 2.0}), UsageError);
  EXPECT_THROW(RateInput::profile({0.0, 1.0}, {0.0}), UsageError);
  // The good ones still work.
  EXPECT_NO_THROW(simulate_open_loop(good, zero, 10 * period));
  EXPECT_EQ(modulation_from_string("sine"), Modulation::sine);
  EXPECT_EQ(modulation_from_string(to_string(Modulation::none)), Modulation::none);
}

TEST(Optics, RateProfileIsInterpolatedLinearlyAndHeldAtTheEnds) {
  const RateInput p = RateInput::profile({1.0, 2.0, 4.0}, {10.0, 20.0, 0.0});
  EXPECT_DOUBLE_EQ(p.at(-5.0), 10.0);
  EXPECT_DOUBLE_EQ(p.at(1.0), 10.0);
  EXPECT_DOUBLE_EQ(p.at(1.5), 15.0);
  EXPECT_DOUBLE_EQ(p.at(2.0), 20.0);
  EXPECT_DOUBLE_EQ(p.at(3.0), 10.0);
  EXPECT_DOUBLE_EQ(p.at(3.5), 5.0);
  EXPECT_DOUBLE_EQ(p.at(4.0), 0.0);
  EXPECT_DOUBLE_EQ(p.at(100.0), 0.0);
  const RateInput one = RateInput::profile({3.0}, {7.0});
  EXPECT_DOUBLE_EQ(one.at(0.0), 7.0);
  EXPECT_DOUBLE_EQ(one.at(9.0), 7.0);
  const RateInput ramp = RateInput::ramp(2.0, 6.0, 4.0);
  EXPECT_DOUBLE_EQ(ramp.at(-1.0), 2.0);
  EXPECT_DOUBLE_EQ(ramp.at(1.0), 3.0);
  EXPECT_DOUBLE_EQ(ramp.at(5.0), 6.0);
}

TEST(Optics, ProfileEqualToRampGivesTheSameOutputsAsTheRamp) {
  const Coil c = lab1_coil(3);
  const double f = proper_frequency(c);
  const double top = 3.0 * omega_pi2(c);
  const double t_ramp = 100.0 / f;
  const RateInput ramp = RateInput::ramp(0.0, top, t_ramp);
  // The profile's middle point is on the ramp; it starts and ends like it.
  const RateInput profile =
      RateInput::profile({0.0, 0.25 * t_ramp, t_ramp}, {0.0, 0.25 * top, top});
  const double duration = 150.0 / f;
  for (const bool closed : {false, true}) {
    const OpticsResult a =
        closed ? simulate_closed_loop(c, ramp, duration) : simulate_open_loop(c, ramp, duration);
    const OpticsResult b = closed ? simulate_closed_loop(c, profile, duration)
                                  : simulate_open_loop(c, profile, duration);
    ASSERT_EQ(a.periods.output.size(), b.periods.output.size());
    ASSERT_GE(a.periods.output.size(), 149u);
    for (std::size_t k = 0; k < a.periods.output.size(); ++k) {
      EXPECT_NEAR(a.periods.rate_rad_s[k], b.periods.rate_rad_s[k], 1e-12 * top) << k;
      EXPECT_NEAR(a.periods.demodulated[k], b.periods.demodulated[k], 1e-9) << k;
      EXPECT_NEAR(a.periods.output[k], b.periods.output[k], 1e-9 * (closed ? top : 1.0)) << k;
    }
  }
}

// --- 6. the delay line ---------------------------------------------------------------

TEST(Optics, DelayLineGivesPlusMinusPiOver2AlternatingEveryTransitTimeAtProperFrequency) {
  for (const int m : {8, 5, 2}) {
    for (const int v : {1, 6}) {
      const Coil c = lab1_coil(v);
      OpticsOptions o;
      o.samples_per_transit = m;
      o.trace_stride = 1;
      const OpticsResult r = simulate_open_loop(c, RateInput::constant(0.2 * omega_pi2(c)),
                                                12.0 / proper_frequency(c), o);
      EXPECT_NEAR(r.sample_interval_s, transit(c) / m, 1e-12 * transit(c));
      const SampleTrace& t = r.trace;
      ASSERT_EQ(t.modulation_rad.size(), static_cast<std::size_t>(r.samples));
      ASSERT_GE(t.modulation_rad.size(), static_cast<std::size_t>(24 * m));
      for (std::size_t k = 0; k < t.modulation_rad.size(); ++k) {
        // Transit j = floor(k / M): +pi/2 in even transits, -pi/2 in odd ones.
        const double expected = (k / static_cast<std::size_t>(m)) % 2 == 0 ? kPi / 2.0 : -kPi / 2.0;
        ASSERT_NEAR(t.modulation_rad[k], expected, 1e-12) << "M " << m << ", sample " << k;
        EXPECT_NEAR(t.time_s[k], static_cast<double>(k) * r.sample_interval_s, 1e-15);
        // The reference is -1 where the difference is +pi/2 (0 in the gate).
        if (t.reference[k] != 0.0) {
          EXPECT_EQ(t.reference[k], expected > 0 ? -1.0 : 1.0);
        }
      }
    }
  }
}

TEST(Optics, TraceKeepsEveryStrideThSampleUpToTheLimit) {
  const Coil c = lab1_coil(1);
  OpticsOptions o;
  o.trace_stride = 3;
  o.trace_limit = 50;
  const OpticsResult r =
      simulate_open_loop(c, RateInput::constant(0.0), 20.0 / proper_frequency(c), o);
  ASSERT_EQ(r.trace.time_s.size(), 50u);
  for (std::size_t i = 0; i < 50; ++i) {
    EXPECT_NEAR(r.trace.time_s[i], static_cast<double>(3 * i) * r.sample_interval_s, 1e-15);
  }
  o.trace_stride = 0;
  EXPECT_TRUE(simulate_open_loop(c, RateInput::constant(0.0), 20.0 / proper_frequency(c), o)
                  .trace.time_s.empty());
}

}  // namespace
}  // namespace foglab::sim
