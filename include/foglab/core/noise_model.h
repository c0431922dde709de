// foglab — the random error model of a gyro: IEEE Std 952 terms plus a
// first-order Gauss-Markov random bias, and their theory. One home for the
// model, shared by the truth (`sim`, which generates it) and the estimators
// (`model`, which identify it); conventions in docs/conventions.md.
//
// The rate of a static gyro, less its systematic part, is a sum of
// independent processes, each with one coefficient (rate in deg/h, tau in s):
//
//   term            symbol  coefficient unit   Allan variance AVAR(tau)        ADEV slope
//   quantisation    Q       deg/h*s            3 Q^2 / tau^2                    -1
//   white rate      N       deg/h/sqrt(Hz)     N^2 / tau                        -1/2
//   flicker         B       deg/h              (2 ln2 / pi) B^2                  0
//   random walk     K       deg/h/sqrt(s)      K^2 tau / 3                      +1/2
//   rate ramp       R       deg/h/s            R^2 tau^2 / 2                    +1
//   Gauss-Markov    GM      sigma deg/h, Tc s  sigma^2 (Tc/tau)^2 (2 tau/Tc - 3 + 4 e^(-tau/Tc) -
//   e^(-2 tau/Tc))
//
// (IEEE Std 952-1997, Annex C, for the first five; the Gauss-Markov term
// follows from its autocorrelation sigma^2 e^(-|t|/Tc). Samples are averages
// of the rate over their interval, as an integrating gyro outputs them.)
// The total is the sum of the terms.
// The lab manual's rho is N and its Wiener q is K.
//
// Two-sided rate PSD S(f) [(deg/h)^2/Hz], with AVAR(tau) = 4 int_0^inf S(f)
// sin^4(pi f tau) / (pi f tau)^2 df (IEEE Std 952, Annex C):
//   N: N^2;  B: B^2 / (2 pi f);  K: K^2 / (2 pi f)^2;  R: R^2 / (2 pi f)^3;
//   Q: (2 pi f)^2 tau0 Q^2 below 1/(2 tau0) for samples every tau0;
//   GM: 2 sigma^2 Tc / (1 + (2 pi f Tc)^2).
//
// Datasheet figures: the angle random walk ARW [deg/sqrt(h)] = N / 60
// (sqrt(1 h) = 60 sqrt(s)); the flicker floor of the Allan deviation is
// sqrt(2 ln2 / pi) B = 0.6643 B, which a datasheet's "bias instability"
// (the minimum of the Allan deviation) equals when flicker alone sets it.
#pragma once

#include <array>
#include <cstdint>
#include <initializer_list>
#include <numbers>
#include <string>
#include <string_view>

namespace foglab {

/// One term of the model (the Gauss-Markov sigma and Tc together).
enum class NoiseTerm { white, flicker, random_walk, ramp, quantisation, gauss_markov };

/// Every term, in the order of the reported parameters (N, B, K, R, Q, GM).
inline constexpr std::array<NoiseTerm, 6> kNoiseTerms = {
    NoiseTerm::white, NoiseTerm::flicker,      NoiseTerm::random_walk,
    NoiseTerm::ramp,  NoiseTerm::quantisation, NoiseTerm::gauss_markov};

/// The term's symbol, as in the JSON and the candidate names: "N", "B",
/// "K", "R", "Q", "GM".
std::string_view to_string(NoiseTerm term);
/// Parses a symbol of to_string(NoiseTerm); throws UsageError otherwise.
NoiseTerm noise_term_from_string(std::string_view text);
/// What the term is, in words: "white rate noise", "flicker (bias
/// instability)", "rate random walk", "rate ramp", "angle quantisation",
/// "first-order Gauss-Markov random bias".
std::string_view describe(NoiseTerm term);

/// A set of terms: the terms a candidate model holds.
class NoiseTermSet {
 public:
  constexpr NoiseTermSet() = default;
  constexpr NoiseTermSet(std::initializer_list<NoiseTerm> terms) {
    for (NoiseTerm t : terms) bits_ |= bit(t);
  }
  /// The set whose bit (1 << term's index in kNoiseTerms) is set in `mask`.
  static constexpr NoiseTermSet from_mask(unsigned mask) {
    NoiseTermSet s;
    s.bits_ = mask & ((1u << kNoiseTerms.size()) - 1u);
    return s;
  }
  constexpr unsigned mask() const { return bits_; }
  constexpr bool empty() const { return bits_ == 0; }
  constexpr bool contains(NoiseTerm t) const { return (bits_ & bit(t)) != 0; }
  constexpr NoiseTermSet with(NoiseTerm t) const { return from_mask(bits_ | bit(t)); }
  constexpr NoiseTermSet without(NoiseTerm t) const { return from_mask(bits_ & ~bit(t)); }
  /// The number of fitted parameters: one per term, two for Gauss-Markov.
  constexpr int parameter_count() const {
    int count = 0;
    for (NoiseTerm t : kNoiseTerms) {
      if (contains(t)) count += t == NoiseTerm::gauss_markov ? 2 : 1;
    }
    return count;
  }
  friend constexpr bool operator==(NoiseTermSet a, NoiseTermSet b) = default;

 private:
  static constexpr unsigned bit(NoiseTerm t) { return 1u << static_cast<unsigned>(t); }
  unsigned bits_ = 0;
};

/// The symbols joined by '+' in kNoiseTerms order ("N+B+K"); "none" when empty.
std::string to_string(NoiseTermSet terms);
/// Parses to_string(NoiseTermSet)'s form; throws UsageError otherwise.
NoiseTermSet noise_term_set_from_string(std::string_view text);

/// The model's coefficients. A term not present is 0.
struct NoiseModel {
  double N = 0.0;         ///< white rate noise [deg/h/sqrt(Hz)] (ARW = N/60 deg/sqrt(h))
  double B = 0.0;         ///< flicker (bias instability) coefficient [deg/h]; ADEV floor 0.664 B
  double K = 0.0;         ///< rate random walk [deg/h/sqrt(s)]
  double R = 0.0;         ///< rate ramp [deg/h/s]
  double Q = 0.0;         ///< angle quantisation [deg/h*s] = quantisation step / sqrt(12)
  double gm_sigma = 0.0;  ///< Gauss-Markov standard deviation [deg/h]
  double gm_tc = 0.0;     ///< its correlation time [s] (> 0 when gm_sigma > 0)

  /// The coefficient of `term` (the Gauss-Markov sigma for gauss_markov).
  double coefficient(NoiseTerm term) const;
  /// Sets it (the Gauss-Markov sigma; Tc is set on its own).
  void set_coefficient(NoiseTerm term, double value);
  /// The terms with a positive coefficient.
  NoiseTermSet terms() const;
};

/// The model's seven parameters in the order they are reported, with their
/// names (as in the JSON), units and meanings.
struct NoiseParameter {
  std::string_view name;     ///< "N", "B", "K", "R", "Q", "gm_sigma", "gm_tc"
  std::string_view unit;     ///< e.g. "deg/h/sqrt(Hz)"
  std::string_view meaning;  ///< a phrase for reports
  NoiseTerm term;            ///< the term it belongs to
  double NoiseModel::*value;
};
inline constexpr std::array<NoiseParameter, 7> kNoiseParameters = {{
    {"N", "deg/h/sqrt(Hz)", "white rate noise (angle random walk = N/60 deg/sqrt(h))",
     NoiseTerm::white, &NoiseModel::N},
    {"B", "deg/h", "flicker, bias instability coefficient (plateau 0.664 B)", NoiseTerm::flicker,
     &NoiseModel::B},
    {"K", "deg/h/sqrt(s)", "rate random walk (Wiener process intensity)", NoiseTerm::random_walk,
     &NoiseModel::K},
    {"R", "deg/h/s", "rate ramp", NoiseTerm::ramp, &NoiseModel::R},
    {"Q", "deg/h*s", "angle quantisation", NoiseTerm::quantisation, &NoiseModel::Q},
    {"gm_sigma", "deg/h", "Gauss-Markov random bias, standard deviation", NoiseTerm::gauss_markov,
     &NoiseModel::gm_sigma},
    {"gm_tc", "s", "Gauss-Markov random bias, correlation time", NoiseTerm::gauss_markov,
     &NoiseModel::gm_tc},
}};

/// The lab's question about the random part of the bias: which process it is.
enum class RandomBiasProcess { none, wiener, gauss_markov };
/// "none", "wiener", "gauss_markov".
std::string_view to_string(RandomBiasProcess process);

// --- datasheet figures -----------------------------------------------------

/// The flicker term's Allan variance per B^2: 2 ln2 / pi (IEEE Std 952, Annex C).
inline constexpr double kFlickerAllanFactor = 2.0 * std::numbers::ln2 / std::numbers::pi;

/// The flat Allan deviation of flicker noise [deg/h]: sqrt(2 ln2 / pi) B = 0.6643 B.
double flicker_floor_deg_h(double b_deg_h);
/// B [deg/h] whose flicker floor is `floor_deg_h` (a datasheet's bias instability).
double flicker_coefficient_deg_h(double floor_deg_h);

/// The angle random walk [deg/sqrt(h)] of white rate noise N [deg/h/sqrt(Hz)]: N / 60.
double arw_deg_sqrt_h(double n_deg_h_sqrt_hz);
/// N [deg/h/sqrt(Hz)] of an angle random walk [deg/sqrt(h)]: 60 ARW.
double white_noise_of_arw(double arw_deg_sqrt_h);

// --- the model's theory ----------------------------------------------------

/// The Allan variance of a unit-variance first-order Gauss-Markov process
/// at tau [s]: (Tc/tau)^2 (2 tau/Tc - 3 + 4 e^(-tau/Tc) - e^(-2 tau/Tc)),
/// by its power series where the closed form would cancel (tau/Tc < 1/4):
/// 2 tau / (3 Tc) at small tau, 2 Tc / tau at large tau.
double gauss_markov_allan_shape(double tau_s, double tc_s);

/// The Allan variance of `term` per unit squared coefficient [1/s, 1, s,
/// s^2, 1/s^2 or 1 for N, B, K, R, Q, GM]; `tc_s` is the Gauss-Markov
/// correlation time (unused by the other terms).
double unit_allan_variance(NoiseTerm term, double tau_s, double tc_s = 1.0);

/// The Allan variance [(deg/h)^2] of one term of `model` at tau [s].
double allan_variance(const NoiseModel& model, NoiseTerm term, double tau_s);
/// The model's Allan variance [(deg/h)^2] at tau [s]: the sum of its terms.
double allan_variance(const NoiseModel& model, double tau_s);

/// The two-sided rate PSD [(deg/h)^2/Hz] of one term at frequency f > 0
/// [Hz]; `sample_interval_s` (tau0) enters the quantisation term only.
double rate_psd(const NoiseModel& model, NoiseTerm term, double frequency_hz,
                double sample_interval_s);

/// Greenhall's generalised structure function of one term's angle
/// (integrated rate) x [(deg/h)^2 s^2] at lag s >= 0 [s], up to a
/// polynomial of degree <= 1 in s: any combination of angle samples whose
/// weights cancel constants and straight lines (the second differences of
/// the Allan variance) has the covariance -1/2 sum_ab w_a u_b D(|t_a - s_b|)
/// (Greenhall, "A structure function representation theorem with
/// applications to frequency stability estimation", IEEE Trans. Instrum.
/// Meas. 32, 1983). AVAR(tau) = (4 D(tau) - D(2 tau)) / (2 tau^2).
///   N: N^2 s;  Q: 2 Q^2 (s > 0);  B: -2 h s^2 ln s, h = B^2 / (2 pi);
///   K: -K^2 s^3 / 6;  GM: 2 sigma^2 Tc^2 (s/Tc - 1 + e^(-s/Tc));  R: 0
///   (a deterministic trend).
/// For N, Q and GM it is the true structure function E[(x(t+s) - x(t))^2].
double angle_structure_function(const NoiseModel& model, NoiseTerm term, double lag_s);

/// The minimum of the model's Allan deviation over a tau range.
struct AdevMinimum {
  double adev_deg_h = 0.0;     ///< [deg/h] the minimum
  double tau_s = 0.0;          ///< [s] where it occurs
  bool at_range_edge = false;  ///< the minimum is at tau_min_s or tau_max_s
};

/// The minimum of sqrt(allan_variance(model, tau)) over [tau_min_s,
/// tau_max_s] on a log grid of `points_per_decade` (refined by golden-
/// section search between the neighbours of the best grid point): the bias
/// instability as the lab and datasheets quote it. Throws UsageError for an
/// empty or non-positive range.
AdevMinimum adev_minimum(const NoiseModel& model, double tau_min_s, double tau_max_s,
                         int points_per_decade = 1000);

/// The longest stretch [octaves] of [tau_min_s, tau_max_s] over which `term`
/// carries at least half of the model's Allan variance (400-step log grid).
/// At 2 or more a record shows the term: a student can read it off the
/// Allan deviation, and the estimators' accuracy goals (docs/validation.md)
/// apply. Throws UsageError for an empty or non-positive range.
double term_dominance_octaves(const NoiseModel& model, NoiseTerm term, double tau_min_s,
                              double tau_max_s);

}  // namespace foglab
