// foglab — the lab manual's eq. (17): the Allan variance a PSD implies,
//
//   sigma_A^2(tau) = (4/pi) int S_y(omega) sin^4(omega tau / 2) / (omega tau)^2 d omega,
//
// the link between the lab's two methods (the PSD and the Allan variance).
// With the two-sided PSD per hertz (white noise flat at N^2, SPEC) it reads
// 4 int_0^inf S(f) sin^4(pi f tau) / (pi f tau)^2 df (IEEE Std 952-1997,
// Annex C). For a record sampled every tau0 the Allan difference of two
// m-sample averages has the response 4 sin^4(pi f tau) / (m sin(pi f tau0))^2
// in place of the sinc (the same for m >> 1, exact for sampled data: it gives
// N^2 / tau and 3 Q^2 / tau^2 at every m), and the record's band ends at the
// Nyquist frequency:
//
//   sigma^2(m tau0) = 4 int_{f_low}^{1/(2 tau0)} S(f) sin^4(pi f m tau0) / (m sin(pi f tau0))^2 df.
//
// Its low end is not 1/T: the Allan difference within a record of length T
// sees the slower fluctuations too (the kernel falls as (f tau)^2 below
// 1/tau, and every random term's integral converges at 0; a lower cut at 1/T
// would take 60 % of a random walk's Allan variance at T/3), so f_low is far
// below 1/T.
//
// foglab evaluates it numerically on the fitted model's PSD (each random
// term's, the sensor bandwidth's power response on the white and flicker
// terms, the output quantisation's known white level) and adds the
// deterministic parts in closed form: the spectral lines (a delta in the PSD)
// and the rate ramp (whose formal PSD R^2 / (2 pi f)^3 is no density: its
// integral diverges at 0), R^2 tau^2 / 2. It compares the result with
// the measured Allan deviation and its 95 % intervals: a check on the fit,
// made through the frequency domain, that no peer draws.
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <vector>

#include "foglab/model/noise_fit.h"
#include "foglab/stats/allan.h"

namespace foglab::model {

/// The fitted model's two-sided rate PSD [(deg/h)^2/Hz] at f [Hz] > 0 for
/// samples every `sample_interval_s`, its random terms: N^2 and the flicker's
/// B^2 / (2 pi f) through the bandwidth's power response, K^2 / (2 pi f)^2,
/// the sampled quantisation 4 Q^2 sin^2(pi f tau0) / tau0, the Gauss-Markov
/// 2 sigma^2 Tc / (1 + (2 pi f Tc)^2), and the known white level's square.
double fitted_rate_psd(const NoiseFitResult& fit, double frequency_hz, double sample_interval_s);

/// Eq. (17) for sampled data (above): the Allan variance [(deg/h)^2] at
/// tau [s] (a multiple m of `sample_interval_s`, rounded to one) of a
/// process whose two-sided PSD is `psd` [(deg/h)^2/Hz], over the band from
/// `low_frequency_hz` (0 < f_low, e.g. 1 / the record's length) to the
/// Nyquist frequency. Relative accuracy about 1e-6 for the model's terms.
/// Throws UsageError for a non-positive tau, sample interval or f_low.
double allan_variance_from_psd(const std::function<double(double)>& psd, double tau_s,
                               double sample_interval_s, double low_frequency_hz);

/// The fitted PSD's Allan deviation (eq. 17) beside the measured one.
struct PsdAllanCheck {
  std::vector<double> tau_s;       ///< [s] the measured taus
  std::vector<double> adev_deg_h;  ///< [deg/h] eq. (17) on the fitted PSD, lines added
  /// Taus compared: those with a 95 % interval from the first the fit used
  /// (NoiseFitResult::first_taus_left_out skipped), and how many of them
  /// have eq. (17) inside the measured 95 % interval.
  int compared = 0;
  int inside_95 = 0;
  /// The largest disagreement: at worst_tau_s eq. (17) is worst_ratio times
  /// the measured deviation, worst_half_widths times the 95 % interval's
  /// half-width on that side on a log scale (above 1: outside it). NaN when
  /// nothing was compared.
  double worst_tau_s = std::numeric_limits<double>::quiet_NaN();
  double worst_ratio = std::numeric_limits<double>::quiet_NaN();
  double worst_half_widths = std::numeric_limits<double>::quiet_NaN();
};

/// Eq. (17) on `fit`'s PSD at `allan`'s taus for a record of `duration_s`
/// [s] sampled every `sample_interval_s` (f_low = 1e-6 / duration), the lines'
/// and the ramp's Allan variance added, against `allan`'s deviations and
/// intervals. Empty (compared 0) for a degenerate fit or a non-rate statistic.
PsdAllanCheck check_allan_against_psd(const NoiseFitResult& fit, const stats::AllanResult& allan,
                                      double sample_interval_s, double duration_s);

}  // namespace foglab::model
