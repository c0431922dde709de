// foglab — lab 1 of the manual ("Исследование линейности выходного сигнала
// ВОГ"), every experiment of its procedure run on the optics model
// (optics.h), for one coil (Table 4's variant or any):
//   1.1   the coil's numbers: K_s, Omega_pi/2, tau0, f_m;
//   2.4-9 the open loop with no, square and sine modulation under a rate
//         ramp over +-Omega_pi/2: intensity against the total phase
//         ("I vs fi"), demodulated output against rate ("S vs Om"), and the
//         time traces at a constant rate (rate, intensity, modulation,
//         output);
//   3.1-6 the ten-rate sweep of the open loop (square modulation; the sine
//         too), scale factors, nonlinearity, and the range at which the
//         nonlinearity is 30 % (bisection to 0.1 %), by the time simulation
//         and by the analytic steady state;
//   4.2   the closed loop under a rate ramp to 3 Omega_pi/2 beside the open
//         loop under the same ramp (the open loop folds), and at a constant
//         rate inside and one beyond the open loop's range: the feedback
//         phase psi (the staircase with its 2 pi resets, Fig. 11) and the
//         output against time;
//   5.1-4 the closed-loop sweep and its nonlinearity;
//   and, beyond the manual, square modulation at half the proper frequency
//   (the transition spikes and the loss of signal, against theory).
#pragma once

#include <array>
#include <optional>

#include "foglab/sim/optics.h"

namespace foglab::sim {

struct Lab1Options {
  OpticsOptions optics;  ///< modulation is set per experiment; the rest applies to all
  ClosedLoopOptions loop;
  SweepOptions sweep;
  int ramp_periods = 4000;            ///< length of the rate ramps [modulation periods]
  int trace_points = 4000;            ///< samples kept from each ramp for "I vs fi"
  int window_periods = 4;             ///< the time traces' window [modulation periods]
  double window_rate_fraction = 0.5;  ///< its constant rate [Omega_pi/2]
  double ramp_range_fraction = 3.0;   ///< the closed-loop ramp's end [Omega_pi/2]
  /// The closed loop's time traces: their constant rates [Omega_pi/2], one
  /// inside the open loop's range and one beyond it, and their length
  /// [modulation periods], from u = 0 (the loop settling, then psi's resets).
  std::array<double, 2> closed_trace_rate_fractions = {0.5, 1.5};
  int closed_trace_periods = 40;
  double off_frequency_ratio = 0.5;   ///< off-frequency experiment: f / f_m, in (0, 1]
  /// Its constant rate [Omega_pi/2] (0.2: the detector's three levels, at
  /// dphi_m = +pi/2, 0 and -pi/2, are far apart).
  double off_frequency_rate_fraction = 0.2;
};

/// One modulation's open-loop experiments.
struct Lab1OpenLoopRun {
  Modulation modulation = Modulation::square;
  OpticsResult ramp;        ///< rate ramp -Omega_pi/2 .. +Omega_pi/2, a decimated trace
  OpticsResult window;      ///< constant rate, every sample of window_periods periods
  double full_scale = 0.0;  ///< 2 gamma (square), 2 gamma J1(phi_m) (sine), 2 gamma (none) [a.u.]
  /// The largest |time simulation - analytic steady state| over the sweep
  /// rates, as a fraction of full scale (square and sine; NaN for none).
  double worst_deviation_of_full_scale = 0.0;
};

struct Lab1Result {
  Coil coil;
  CoilNumbers numbers;
  std::array<Lab1OpenLoopRun, 3> open_loop;  ///< none, square, sine
  SweepResult sweep_square;                  ///< time simulation
  SweepResult sweep_square_analytic;
  SweepResult sweep_sine;
  SweepResult sweep_closed;
  std::optional<double> range_30_rad_s;           ///< time simulation [rad/s]
  std::optional<double> range_30_analytic_rad_s;  ///< analytic [rad/s]
  OpticsResult closed_ramp;  ///< closed loop, rate 0 .. ramp_range_fraction Omega_pi/2
  OpticsResult open_ramp;    ///< open loop (square) under the same ramp
  /// The closed loop at closed_trace_rate_fractions: per modulation period,
  /// and every sample traced (psi's steps).
  std::array<OpticsResult, 2> closed_traces;
  /// Square modulation at off_frequency_ratio f_m, constant rate, every sample.
  OpticsResult off_frequency;
  double off_frequency_signal_ratio = 0.0;  ///< S(f) / S(f_m), simulated
  double off_frequency_theory_ratio = 0.0;  ///< the same from theory (with the gating)
  /// Fraction of the off-frequency samples whose modulation phase difference is 0.
  double off_frequency_spike_fraction = 0.0;
};

/// Runs lab 1 on `coil`. Throws UsageError for bad options.
Lab1Result run_lab1(const Coil& coil, const Lab1Options& options = {});

}  // namespace foglab::sim
