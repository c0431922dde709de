// foglab — internals of the synthetic-recording generator (not installed).
//
// * Counter-based random numbers: every deviate is a pure function of
//   (seed, stream, process id, index). A 64-bit key is hashed from
//   (seed, stream, process id); deviate `index` of that process uses the
//   64-bit word wyrand(key + index * increment), i.e. output number `index`
//   of Wang Yi's wyrand generator started at the key (a counter-based use of
//   it); keys are hashed with SplitMix64 (Steele, Lea & Flood 2014).
//   Normals come from that word through the ziggurat method with 256 layers
//   (Marsaglia & Tsang 2000, J. Stat. Software 5(8), in Doornik's 2005
//   variant "An Improved Ziggurat Method to Generate Normal Random Samples"):
//   8 bits choose the layer, 53 bits give a signed uniform; the rare
//   rejections (about 1 %) draw further words by re-hashing, still a pure
//   function of the same counter. Uniforms use the top 53 bits.
// * Exact steps of a first-order Gauss-Markov (Ornstein-Uhlenbeck) process
//   together with its average over the step.
// * The flicker-noise bank (docs/theory/flicker.md).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

namespace foglab::sim::detail {

inline constexpr std::uint64_t kGolden = 0x9e3779b97f4a7c15ULL;

/// SplitMix64 output function (Stafford's variant 13 finaliser) of z + golden.
inline std::uint64_t mix64(std::uint64_t z) {
  z += kGolden;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/// The key of one random process of one run.
inline std::uint64_t process_key(std::uint64_t seed, std::uint64_t stream, std::uint64_t process) {
  std::uint64_t k = mix64(seed ^ 0x243f6a8885a308d3ULL);
  k = mix64(k ^ mix64(stream + 0x13198a2e03707344ULL));
  return mix64(k ^ mix64(process + 0xa4093822299f31d0ULL));
}

/// The 64-bit word number `index` of the process with key `key`: the output
/// of wyrand (Wang Yi's wyhash PRNG: a Weyl sequence with one 64x64->128-bit
/// multiply-fold per output) for the counter key + index * increment.
__extension__ using Uint128 = unsigned __int128;
inline std::uint64_t word_at(std::uint64_t key, std::uint64_t index) {
  const std::uint64_t s = key + index * 0xa0761d6478bd642fULL;
  const Uint128 t = static_cast<Uint128>(s) * (s ^ 0xe7037ed1a0b428dbULL);
  return static_cast<std::uint64_t>(t >> 64) ^ static_cast<std::uint64_t>(t);
}

/// Uniform on [0, 1) from the top 53 bits of a word.
inline double uniform_of(std::uint64_t word) { return static_cast<double>(word >> 11) * 0x1.0p-53; }

/// Ziggurat tables (256 layers).
struct Ziggurat {
  static constexpr int kLayers = 256;
  double x[kLayers + 1];
  double f[kLayers + 1];  ///< exp(-x^2/2)
  double ratio[kLayers];
  double r;
};

/// The tables, built once.
const Ziggurat& ziggurat();

/// The rejection branch of normal_of() (about 1 % of the draws).
double normal_slow(const Ziggurat& z, std::uint64_t word);

/// A standard normal deviate from one word (plus re-hashed words if rejected).
inline double normal_of(const Ziggurat& z, std::uint64_t word) {
  const unsigned layer = static_cast<unsigned>(word & 0xFFu);
  const double u = static_cast<double>(static_cast<std::int64_t>(word) >> 11) * 0x1.0p-52;  // [-1, 1)
  if (std::fabs(u) < z.ratio[layer]) return u * z.x[layer];
  return normal_slow(z, word);
}

inline double normal_at(const Ziggurat& z, std::uint64_t key, std::uint64_t index) {
  return normal_of(z, word_at(key, index));
}

// --- Ornstein-Uhlenbeck (first-order Gauss-Markov) process -------------------
//
// dX = -X/Tc dt + sqrt(2 sigma^2/Tc) dW, stationary variance sigma^2. Over a
// step h (x = h/Tc, rho = e^-x), with A the average of X over the step:
//   X_{k+1} = rho X_k + e1,          Var e1 = sigma^2 (1 - rho^2)
//   A_k     = beta X_k + e2,         beta = (1 - rho)/x
//   Var e2  = 2 sigma^2 x g(x),      g(x) = [x - 2(1 - e^-x) + (1 - e^-2x)/2] / x^3
//   Cov(e1, e2) = 2 sigma^2 x c(x),  c(x) = [(1 - e^-x) - (1 - e^-2x)/2] / x^2
// (integrals of the OU kernel; for x -> 0 they become the Brownian values
// 2 sigma^2/Tc * h/3 and h/2).

/// Step coefficients for unit sigma: A_k = beta X_k + s_avg_state xi1 + s_avg xi2,
/// X_{k+1} = rho X_k + s_state xi1, xi1, xi2 independent standard normals.
struct OuStep {
  double rho = 0.0;
  double beta = 0.0;
  double s_state = 0.0;
  double s_avg_state = 0.0;
  double s_avg = 0.0;
};

OuStep ou_step(double tc_s, double h_s);

// The Allan variance of a unit-variance OU process is
// foglab::gauss_markov_allan_shape() (core/noise_model.h).

// --- Flicker bank ------------------------------------------------------------

/// One OU component of the flicker bank, for B = 1 deg/h.
struct FlickerComponent {
  double tc_s = 0.0;      ///< correlation time [s]
  double variance = 0.0;  ///< [(deg/h)^2] for B = 1 deg/h
  int level = 0;          ///< updated every 2^level samples (0: every sample, exact average)
};

struct FlickerDesign {
  std::vector<FlickerComponent> components;
  double fit_tau_min_s = 0.0;  ///< calibration range [s]
  double fit_tau_max_s = 0.0;
  double max_relative_error = 0.0;  ///< of the calibrated (exact) bank over the fit range
};

/// Correlation times per decade.
inline constexpr int kFlickerPerDecade = 3;
/// A component is updated every D = 2^level samples with D <= Tc / (ratio tau0).
inline constexpr double kFlickerDecimationRatio = 32.0;
/// Coarsest update interval 2^level (divides the block length 2^20).
inline constexpr int kFlickerMaxLevel = 12;

/// The calibrated bank for sample rate fs and record length duration_s.
FlickerDesign design_flicker(double sample_rate_hz, double duration_s);

/// Allan variance of the bank (every component exact, no decimation).
double flicker_bank_allan_variance(const FlickerDesign& design, double tau_s);

}  // namespace foglab::sim::detail
