// foglab — the lab-2 variant data sets and their answer key (instructor side).
//
// Lab 2 of the manual (Table 5) gives each student a variant k = 1..6 and two
// files, FOG1_k.mat and FOG2_k.mat, each holding `f, t, Y1, Y2, T1, T2`: the
// rate of a static gyro at constant temperature (Y1, T1: a thermostat with a
// small sensor jitter) and during a linear 10 degC temperature ramp (Y2, T2).
// The student fits p = polyfit(T, Y, 2), reads the white-noise intensity,
// the random-bias process (Wiener or first-order Gauss-Markov, and its
// intensity) and the bias instability from the PSD and the Allan deviation,
// and names each gyro's accuracy class (Table 1).
//
// Design (deterministic in (seed, variant): each parameter is drawn from its
// range by a hash of seed, variant, gyro and parameter number):
//   * FOG1 — closed-loop, intermediate grade: 10 Hz for 3 h; ARW
//     0.006..0.02 deg/sqrt(h); flicker floor 0.664 B 0.02..0.06 deg/h;
//     temperature coefficients |c1| 0.15..0.4 deg/h/degC, |c2| 0.005..0.02.
//   * FOG2 — open-loop, tactical grade: 20 Hz for 2 h; ARW 0.08..0.25
//     deg/sqrt(h); flicker floor 1..2.5 deg/h; |c1| 2..4 deg/h/degC,
//     |c2| 0.05..0.2.
//   * the random bias is a Wiener process in odd variants for FOG1 and even
//     variants for FOG2, otherwise a first-order Gauss-Markov process, so
//     each variant has one gyro of each kind. It is placed so that the
//     record shows it, since the lab asks which process it is: it carries at
//     least half the Allan variance over at least two octaves of the usable
//     tau range (random_bias_octaves, also in the answer key). With the
//     range's end tau_u = duration / 10 (1080 s for FOG1, 720 s for FOG2):
//       - Wiener: K such that the random walk's Allan variance K^2 tau / 3
//         equals that of white noise and flicker at tau_w = tau_u / 2^u,
//         u drawn in 2.5..4 octaves (FOG1: tau_w 68..191 s, FOG2 45..127 s);
//       - Gauss-Markov: the ADEV hump (0.62 sigma at 1.89 Tc) at
//         tau_u / 2^g, g in 2..3.5 octaves (FOG1: Tc 51..143 s, FOG2
//         34..95 s), and 2..4 times the ADEV of white noise and flicker
//         there.
//   * c1 and c2 are scaled up together where needed so that the ramp moves
//     the bias (|c1| x 5 degC at the ends) by at least 0.75 of what the noise
//     wanders over the run, K sqrt(duration) or sigma plus three flicker
//     floors plus N / sqrt(duration): the lab's first question needs the
//     temperature law to show as its second needs the random bias to show.
//     A visible random walk wanders far over hours, so FOG2's |c1| reaches
//     about 20 deg/h/degC in its strongest Wiener variants.
//   * constant bias drawn in +-(0.5..3) deg/h (FOG1), +-(5..25) deg/h (FOG2);
//     no input rate (the sensitive axis is taken horizontal, pointing east,
//     so it sees no Earth rate); thermostat at T0 uniform in 22..28 degC with
//     0.02 degC jitter; the ramp runs from T0 - 5 to T0 + 5 degC (same T_ref).
//   * generator streams: stream = 100 variant + 10 gyro + run (gyro 1|2,
//     run 1 constant|2 ramp), all with the one seed.
//
// Answer key: computed from the model, never estimated from data — the
// polynomial the lab's polyfit should approach, N/ARW/K/GM, and the bias
// instability = the minimum of the model's theoretical ADEV (IEEE 952, see
// core/noise_model.h) over the record's usable tau range [1/fs, duration/10]
// (at least 10 clusters, the manual's L_m >= 10), with its tau, and the
// Table 1 class (the worse of the bias-instability and ARW classes).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "foglab/core/accuracy_class.h"
#include "foglab/core/noise_model.h"
#include "foglab/sim/error_model.h"
#include "foglab/sim/generator.h"

namespace foglab::sim {

// Table 1 accuracy classes live in core (shared with the estimators).
using foglab::AccuracyClass;
using foglab::class_by_arw;
using foglab::class_by_bias_instability;
using foglab::classify;
using foglab::ClassVerdict;
using foglab::to_string;
// The model's theory (Allan variance, ADEV minimum, term dominance) and the
// random-bias processes live in core (shared with the estimators).
using foglab::AdevMinimum;
using foglab::RandomBiasProcess;

// --- the answer key's theory --------------------------------------------------

/// The systematic part bias + input_rate + sum_k c_k (T - t_ref_c)^k as a
/// polynomial in raw T [degC]: ascending coefficients a_0, a_1, ... [deg/h/degC^j].
std::vector<double> raw_temperature_polynomial(const ErrorModel& model, double t_ref_c);

// --- the variants -----------------------------------------------------------

/// The seed used when none is given (the manual's year).
inline constexpr std::uint64_t kLab2DefaultSeed = 2021;

struct Lab2Options {
  std::uint64_t seed = kLab2DefaultSeed;
  /// [s] overrides every run's duration (tests, quick looks); the answer
  /// key follows (its usable tau range shrinks).
  std::optional<double> duration_s;
};

/// One run of a gyro and what the lab should find in it.
struct Lab2Run {
  std::string rate_name;         ///< "Y1" | "Y2"
  std::string temperature_name;  ///< "T1" | "T2"
  TemperatureProfile temperature;
  GeneratorOptions generator;  ///< fs, duration, seed, stream
  double t_ref_c = 0.0;        ///< [degC] reference of the temperature coefficients

  // answer key, from the model
  /// p of polyfit(T, Y, 2) in MATLAB order [p1 p2 p3] (deg/h per degC^2,
  /// degC, 1): the model's polynomial expanded in raw degC.
  std::array<double, 3> polyfit_p{};
  double lab_constant_term_deg_h = 0.0;  ///< p3: the polynomial at T = 0 degC
  double bias_at_t_ref_deg_h = 0.0;      ///< the polynomial at t_ref_c
  /// False for the thermostat run: its temperature moves only by the sensor
  /// jitter, so polyfit(T1, Y1, 2) is ill-conditioned and its constant term
  /// is dominated by noise; compare the bias at T_ref (mean of Y1) instead.
  bool constant_term_well_conditioned = false;
  double usable_tau_min_s = 0.0;  ///< [s] 1/fs
  double usable_tau_max_s = 0.0;  ///< [s] duration/10
  AdevMinimum bias_instability;   ///< min of the model ADEV in the usable range
  /// [octaves] of the usable range over which the random bias (Wiener or
  /// Gauss-Markov) carries at least half the Allan variance
  /// (term_dominance_octaves); at least 2 in the design's duration.
  double random_bias_octaves = 0.0;
};

/// One gyro of a variant (the file FOGg_k.mat).
struct Lab2Gyro {
  int gyro = 1;           ///< 1 | 2
  std::string name;       ///< "FOG1" | "FOG2"
  std::string file_name;  ///< "FOG1_3.mat"
  std::string design;     ///< a sentence describing the gyro
  ErrorModel model;       ///< the truth (SPEC units)
  RandomBiasProcess random_bias = RandomBiasProcess::wiener;  ///< wiener | gauss_markov
  double arw_deg_sqrt_h = 0.0;                                ///< arw_deg_sqrt_h(N): N / 60
  std::array<Lab2Run, 2> runs;  ///< constant temperature (Y1, T1), ramp (Y2, T2)
  ClassVerdict verdict;         ///< from the (shared) bias instability and ARW
};

struct Lab2Variant {
  int variant = 1;  ///< 1..6
  std::uint64_t seed = kLab2DefaultSeed;
  std::array<Lab2Gyro, 2> gyros;  ///< FOG1, FOG2
};

inline constexpr int kLab2Variants = 6;

/// Variant k (1..6; UsageError otherwise, or for a duration <= 0).
Lab2Variant lab2_variant(int variant, const Lab2Options& options = {});

/// All six.
std::vector<Lab2Variant> lab2_variants(const Lab2Options& options = {});

}  // namespace foglab::sim
