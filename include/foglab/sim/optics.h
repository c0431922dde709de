// foglab — the FOG optical signal chain of lab 1 (docs/conventions.md
// section 7; the lab manual's section 1 and "Исследование линейности выходного сигнала ВОГ"),
// the equivalent of its Simulink models fog_open_loop.slx and
// fog_closed_loop.slx.
//
// Coil (manual formulas (1) and (9)). A coil of fibre length L wound on
// radius R, light of wavelength lambda:
//   Sagnac phase          phi_s = K_s Omega,   K_s = 4 pi R L / (lambda c)  [s]
//   range                 Omega_pi/2 = (pi/2) / K_s                         [rad/s]
//   transit time          tau0 = n_g L / c   (the manual: n_g = 1)          [s]
//   proper frequency      f_m = 1 / (2 tau0)                                [Hz]
//
// Interferometer and detector (formula (2)): the two waves meet with the
// phase difference phi_s + dphi_m(t), where the reciprocal modulator at one
// end of the coil adds dphi_m(t) = phi_m(t) - phi_m(t - tau0) (Table 2: one
// wave passes it on entering, the other on leaving the coil, tau0 later), so
//   I(t) = I0/2 (1 + cos(phi_s + dphi_m(t))),     v(t) = G I(t)
// with I0 the source intensity and G the detector gain [a.u.]. The time
// simulation samples at dt = tau0 / M (M = samples per transit, 8 by
// default: 16 samples per modulation period at f_m) and takes
// phi_m(t - tau0) from a delay line of M samples.
//
// Modulation (the modulator's drive phi_m):
//   * none;
//   * square: phi_m = +-pi/4 switching every half period 1/(2 f); at f = f_m
//     the phase difference switches between +pi/2 and -pi/2 (formulas (3),
//     (4)); away from f_m it spends part of each half period at 0 — the
//     "transition spikes" — and the signal falls by the fraction 2 f tau0
//     (f < f_m);
//   * sine: phi_m(t) = a sin(2 pi f t), whose phase difference is
//     2 a sin(pi f tau0) cos(2 pi f (t - tau0/2)); a is set so that its
//     amplitude at f_m is phi_m (default 1.8 rad, where J1 is near its
//     maximum 0.58; formula (8)).
//
// Synchronous detection at the modulation frequency: the detector output is
// multiplied by the reference, -1/+1 in the half periods where the phase
// difference is +pi/2 / -pi/2 (square), -cos(2 pi f (t - tau0/2)) (sine),
// averaged over each whole modulation period (the samples of the first
// `gate_fraction` of each half period after a square edge left out) and
// doubled, then smoothed by a first-order low-pass. In the steady state
// (analytic path, steady_state_output()):
//   square: S = 2 gamma sin(phi_s)            (formula (5), gamma = G I0/2)
//   sine:   S = 2 gamma J1(phi_m) sin(phi_s)  (formula (8), C = 2 gamma)
//   none:   the detector's mean, gamma (1 + cos phi_s) (no demodulation).
//
// Closed loop (manual section 1.3): square bias modulation plus a digital
// staircase phase ramp psi on the same modulator: psi grows by the feedback
// step u at every transit time and is kept in [0, 2 pi) by resets, so the
// ramp adds the phase difference psi(t) - psi(t - tau0) = u (mod 2 pi, which
// the interferometer cannot tell apart). An integrating controller updates
// u once per modulation period from the normalised demodulated error
// e = S / (2 gamma) = sin(phi_s + u):  u <- u - g e  (loop gain g). Locked,
// u = -phi_s, and the output is the rate -u / K_s: linear and not limited to
// Omega_pi/2 (the error sees phi_s + u near 0). A ramp of input rate is
// followed with a lag of (phase change per period) / g.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace foglab::sim {

/// Speed of light in vacuum [m/s] (exact, SI).
inline constexpr double kSpeedOfLightM_S = 299792458.0;

/// A fibre coil and its light source.
struct Coil {
  double length_m = 0.0;      ///< fibre length L [m]
  double radius_m = 0.0;      ///< winding radius R [m]
  double wavelength_m = 0.0;  ///< source wavelength lambda [m]
  double group_index = 1.0;   ///< n_g of the transit time (the manual's formula: 1)
};

/// What the lab asks the student to compute (item 1.1).
struct CoilNumbers {
  double scale_factor_s = 0.0;           ///< K_s = phi_s / Omega [rad per rad/s = s]
  double omega_pi2_rad_s = 0.0;          ///< Omega_pi/2 [rad/s]
  double omega_pi2_deg_s = 0.0;          ///< Omega_pi/2 [deg/s]
  double transit_time_s = 0.0;           ///< tau0 [s]
  double modulation_frequency_hz = 0.0;  ///< f_m = 1/(2 tau0) [Hz]
};

/// The physical ranges a coil is checked against: far wider than any gyro
/// (lengths of 1 m to 10 km, radii of 1 to 20 cm, 0.8 to 1.6 um sources),
/// narrow enough that every derived number is finite.
inline constexpr double kMaxFibreLengthM = 1e6;  ///< 1000 km
inline constexpr double kMaxCoilRadiusM = 100.0;
inline constexpr double kMinWavelengthM = 1e-7;  ///< 100 nm
inline constexpr double kMaxWavelengthM = 1e-4;  ///< 100 um
inline constexpr double kMaxGroupIndex = 10.0;
/// The largest input rate or sweep range [rad/s] the simulations take
/// (about 5.7 million deg/s).
inline constexpr double kMaxInputRateRadS = 1e5;
/// The highest modulation frequency [Hz] a simulation takes.
inline constexpr double kMaxModulationFrequencyHz = 1e12;

/// The coil's numbers. Throws UsageError naming the quantity for a length,
/// radius, wavelength or group index outside (0, max] (the group index:
/// [1, max]; the wavelength: [min, max]).
CoilNumbers coil_numbers(const Coil& coil);

inline constexpr int kLab1Variants = 6;
/// The manual's Table 4, variant 1..6 (UsageError otherwise).
Coil lab1_coil(int variant);

enum class Modulation { none, square, sine };
std::string_view to_string(Modulation m);
/// "none" | "square" | "sine"; UsageError otherwise.
Modulation modulation_from_string(std::string_view text);

/// The true input rate against time.
struct RateInput {
  enum class Kind { constant, ramp, profile };
  Kind kind = Kind::constant;
  double rate_rad_s = 0.0;            ///< constant: the rate; ramp: the start [rad/s]
  double end_rate_rad_s = 0.0;        ///< ramp: the rate at ramp_duration_s [rad/s]
  double ramp_duration_s = 0.0;       ///< ramp: then held at end_rate_rad_s [s]
  std::vector<double> time_s;         ///< profile: increasing times [s]
  std::vector<double> profile_rad_s;  ///< profile: rates, linear between, held at the ends

  static RateInput constant(double rate_rad_s);
  static RateInput ramp(double start_rad_s, double end_rad_s, double duration_s);
  /// Throws UsageError unless times are finite, strictly increasing and as
  /// many as the rates (at least one).
  static RateInput profile(std::vector<double> time_s, std::vector<double> rate_rad_s);
  double at(double t_s) const;  ///< [rad/s]
};

struct OpticsOptions {
  Modulation modulation = Modulation::square;
  double sine_amplitude_rad = 1.8;       ///< phi_m: phase-difference amplitude at f_m
  double modulation_frequency_hz = 0.0;  ///< 0: the proper frequency f_m = 1/(2 tau0)
  int samples_per_transit = 8;           ///< M: dt = tau0/M (16 per period at f_m); >= 2
  double source_intensity = 1.0;         ///< I0 [a.u.]
  double detector_gain = 1.0;            ///< G [a.u.]
  double gate_fraction = 0.125;          ///< of each half period after a square edge, left out
  double lowpass_periods = 20.0;         ///< low-pass time constant [modulation periods]
  /// Sample-by-sample traces: every trace_stride-th sample is kept (0: none),
  /// at most trace_limit of them.
  std::int64_t trace_stride = 0;
  std::size_t trace_limit = 100000;
};

struct ClosedLoopOptions {
  double loop_gain = 0.5;         ///< g of u <- u - g e (0 < g < 2 is stable)
  double initial_step_rad = 0.0;  ///< u at t = 0
};

/// Every `trace_stride`-th sample of the simulation.
struct SampleTrace {
  std::vector<double> time_s;            ///< [s]
  std::vector<double> rate_rad_s;        ///< input rate [rad/s]
  std::vector<double> sagnac_phase_rad;  ///< phi_s [rad]
  std::vector<double> modulation_rad;    ///< phase difference from the modulator [rad]
  std::vector<double> total_phase_rad;   ///< phi_s + modulation [rad]
  std::vector<double> detector;          ///< v = G I [a.u.]
  std::vector<double> reference;         ///< the demodulation reference (0: gated)
  /// Closed loop: the feedback phase psi [rad], the staircase in [0, 2 pi);
  /// empty in open loop.
  std::vector<double> ramp_phase_rad;
};

/// One value per modulation period.
struct PeriodSeries {
  std::vector<double> time_s;      ///< [s] end of the period
  std::vector<double> rate_rad_s;  ///< input rate, mean over the period [rad/s]
  /// Open loop: the demodulated signal S [a.u.] (modulation none: the
  /// detector's mean). Closed loop: the normalised error e = sin(phi_s + u).
  std::vector<double> demodulated;
  /// Open loop: S after the low-pass [a.u.]. Closed loop: the output rate
  /// -u/K_s [rad/s] (u as applied during the period).
  std::vector<double> output;
  std::vector<double> feedback_step_rad;  ///< closed loop: u [rad]; empty in open loop
  /// Closed loop: the feedback phase psi [rad] at the period's end, the
  /// staircase that steps by u every transit time and is reset by 2 pi
  /// whenever it leaves [0, 2 pi) (the sawtooth of the manual's Fig. 11);
  /// empty in open loop.
  std::vector<double> ramp_phase_rad;
};

struct OpticsResult {
  CoilNumbers coil;
  double sample_interval_s = 0.0;        ///< dt [s]
  double modulation_frequency_hz = 0.0;  ///< as simulated [Hz]
  std::int64_t samples = 0;
  PeriodSeries periods;
  SampleTrace trace;
  /// gamma = G I0 / 2 [a.u.]: the open-loop full scale is 2 gamma (square)
  /// or 2 gamma J1(phi_m) (sine).
  double gamma = 0.0;
};

/// Simulates the open-loop gyro for `duration_s`. Throws UsageError for bad
/// options (a non-positive duration, M < 2, gate_fraction outside [0, 0.5),
/// a non-positive modulation frequency or intensity).
OpticsResult simulate_open_loop(const Coil& coil, const RateInput& rate, double duration_s,
                                const OpticsOptions& options = {});

/// Simulates the closed-loop gyro (square bias modulation; options.modulation
/// is ignored).
OpticsResult simulate_closed_loop(const Coil& coil, const RateInput& rate, double duration_s,
                                  const OpticsOptions& options = {},
                                  const ClosedLoopOptions& loop = {});

/// The analytic steady state of the open loop at a constant rate (the
/// formulas above), at the options' modulation frequency: square S = 2 gamma
/// r sin(phi_s), sine 2 gamma J1(phi_eff) sin(phi_s), none gamma (1 + cos
/// phi_s), with r = 2 f tau0 (f <= f_m; 1 at f_m) and phi_eff the sine's
/// phase-difference amplitude at f. Ignores gating.
double steady_state_output(const Coil& coil, double rate_rad_s, const OpticsOptions& options = {});

// --- the lab's procedures -----------------------------------------------------

/// The lab's ten rates: -range .. +range in steps of range/5, zero left out
/// (items 3.3 and 5.2) [same unit as range].
std::vector<double> lab_sweep_rates(double range);

/// (max SF - min SF) / mean SF in %, SF = output/rate (items 3.5, 5.4).
/// Throws UsageError for mismatched sizes, no rates or a zero rate.
double nonlinearity_percent(std::span<const double> rates, std::span<const double> outputs);

enum class SweepMethod { time, analytic };

struct SweepOptions {
  SweepMethod method = SweepMethod::time;
  /// Time simulation: the rate is brought from 0 to its value over the
  /// first half of `settle_periods` modulation periods (the closed loop must
  /// acquire it), held, and the output averaged over the `average_periods`
  /// after the settling.
  int settle_periods = 400;
  int average_periods = 400;
};

struct SweepResult {
  bool closed_loop = false;
  std::vector<double> rates_rad_s;    ///< [rad/s]
  std::vector<double> outputs;        ///< open loop S [a.u.]; closed loop the output rate [rad/s]
  std::vector<double> scale_factors;  ///< outputs / rates: [a.u. per rad/s] | dimensionless
  double nonlinearity_percent = 0.0;
  /// Closed loop: the feedback phase step u [rad], averaged over the same
  /// periods as the outputs (analytic: -K_s rate): the manual's output
  /// (items 4.2 and 5.2); empty in open loop.
  std::vector<double> feedback_steps_rad;
  /// true: outputs are the feedback phase u [rad] and scale factors u / rate
  /// [s] (-K_s), feedback_phase_form()'s; false: the rate form above.
  bool phase_form = false;
};

/// A closed-loop sweep in the manual's form (lab 1, items 5.2-5.4): its
/// outputs are the feedback phase steps u [rad], its scale factors u / rate
/// [s] (-K_s), and its nonlinearity is recomputed from them (the same
/// number: the phase is -K_s times the rate output). Throws UsageError for
/// an open-loop sweep.
SweepResult feedback_phase_form(const SweepResult& closed_loop);

/// The lab's sweep over +-range_rad_s (the manual: Omega_pi/2).
SweepResult sweep_open_loop(const Coil& coil, double range_rad_s, const OpticsOptions& options = {},
                            const SweepOptions& sweep = {});
SweepResult sweep_closed_loop(const Coil& coil, double range_rad_s,
                              const OpticsOptions& options = {}, const ClosedLoopOptions& loop = {},
                              const SweepOptions& sweep = {});

/// The range whose open-loop ten-rate sweep has the given nonlinearity
/// (item 3.6: 30 %), by bisection on the range until it is known to
/// `relative_tolerance` (0.1 %), within (0, Omega_pi/2]. Empty when even
/// Omega_pi/2 stays below the target. [rad/s]
std::optional<double> range_for_nonlinearity(const Coil& coil, double target_percent = 30.0,
                                             const OpticsOptions& options = {},
                                             const SweepOptions& sweep = {},
                                             double relative_tolerance = 1e-3);

}  // namespace foglab::sim
