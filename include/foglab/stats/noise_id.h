// foglab — identification of the dominant power-law noise at one tau.
//
// Power-law model S_y(f) = h_alpha f^alpha for the rate (fractional
// frequency) record: alpha = +2 white PM (angle white noise: in a gyro,
// quantisation), +1 flicker PM, 0 white FM (angle random walk), -1 flicker FM
// (bias instability), -2 random-walk FM (rate random walk), and for the
// Hadamard family -3, -4.
//
// Methods, as Stable32 uses them (NIST SP 1065 section 5.6):
//   * lag-1 autocorrelation (W. J. Riley and C. A. Greenhall, "Power law
//     noise identification using the lag 1 autocorrelation", Proc. 18th
//     EFTF, 2004): the angle record is decimated by m, a quadratic removed,
//     and it is differenced d = 0, 1, ... times until rho = r1/(1+r1) < 0.25
//     or d = d_max; then alpha = 2 - 2 d - round(2 rho). Used while at least
//     30 decimated points remain;
//   * otherwise the B1 bias ratio (Barnes 1969; SP1065 eq. 73: standard
//     variance over Allan variance of the m-sample averages) compared with
//     its theoretical values at the geometric means between noise types,
//     and, where B1 says phase noise, the R(n) = MVAR/AVAR ratio to split
//     white from flicker PM (SP1065 section 5.6.2). B1 is used while at
//     least 7 averages remain; below that the previous tau's type holds.
//     These are Stable32's rules: on its PHASE.DAT tables foglab's alpha
//     agrees at 136 of 139 OADEV taus (docs/theory/allan.md).
// allan_deviation() adds by default one physical constraint (NoiseRules,
// allan.h): phase-noise types fall as 1/tau, faster than any other term, so
// beyond the shortest tau identified as frequency noise a PM call is taken
// as white FM (method "...,fm_floor").
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace foglab::stats {

/// How a noise type was identified.
enum class NoiseIdMethod {
  off,       ///< not identified (intervals were not asked for; alpha is 0)
  none,      ///< too few averages for any method (the previous tau's alpha holds)
  lag1_acf,  ///< the lag-1 autocorrelation
  b1,        ///< Barnes' B1 ratio
  b1_rn,     ///< B1, with the R(n) ratio for phase noise
};
/// "" (off), "none", "lag1_acf", "b1", "b1_rn".
std::string_view to_string(NoiseIdMethod method);

struct NoiseId {
  int alpha = 0;  ///< identified integer exponent
  NoiseIdMethod method = NoiseIdMethod::none;
  double rho = 0.0;     ///< lag-1 method: the final rho estimate
  int differences = 0;  ///< lag-1 method: number of differences taken
};

/// How allan_deviation() set a point's alpha: the method, and whether a
/// phase-noise call beyond the shortest frequency-noise tau was taken as
/// white FM (the "fm_floor" above).
struct AlphaMethod {
  NoiseIdMethod method = NoiseIdMethod::off;
  bool fm_floor = false;
};
/// The method's name, with ",fm_floor" when that applied: "lag1_acf",
/// "b1,fm_floor", ... ("" when off).
std::string to_string(const AlphaMethod& method);

/// Identifies the noise at averaging factor m of an angle record (tau0 = 1
/// units, as made by to_phase()). d_max = 2 for the Allan and modified
/// families, 3 for Hadamard. The result is clamped to the exponents for which
/// the statistic converges: [-2, 2] for d_max = 2, [-4, 2] for d_max = 3.
NoiseId identify_noise(std::span<const double> phase, std::int64_t m, int d_max);

/// The same for several averaging factors at once, in two passes over the
/// record whatever their number (the form allan_deviation() uses).
std::vector<NoiseId> identify_noise(std::span<const double> phase,
                                    std::span<const std::int64_t> factors, int d_max);

/// Lag-1 autocorrelation r1 of a series (Riley & Greenhall eq. 2).
double lag1_autocorrelation(std::span<const double> series);

}  // namespace foglab::stats
