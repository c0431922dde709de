// foglab — the lab's random-bias question (is the slow part of the bias a
// Wiener process, a first-order Gauss-Markov process, or not visible?)
// answered by the exact likelihood of the record's block means.
//
// Why not the Allan-variance fit alone: when the Gauss-Markov hump lies at
// the end of the usable tau range (the lab-2 records: Tc of minutes, a
// record of two or three hours), the few long-tau Allan points carry little
// information and correlate strongly, and the fit confuses the two
// processes in about one run in six. The lowest frequencies of the record
// decide it: below 1/(2 pi Tc) a Gauss-Markov spectrum is flat where a
// random walk's keeps rising as 1/f^2.
//
// Method. The residual rate is averaged over `blocks` equal blocks of
// tau_b seconds; the differences of consecutive block means form a
// stationary Gaussian series whose covariance follows exactly from the
// phase structure function of each term (block_covariance.h): white N^2,
// flicker B^2, Wiener K^2 and Gauss-Markov (sigma^2, Tc) alike. Its
// restricted likelihood (REML: the likelihood of the contrasts orthogonal to
// the temperature polynomial's columns, Harville 1974) is evaluated by the
// Durbin-Levinson recursion in O(blocks^2). N is held at the Allan fit's
// value (at tau_b it is fixed by the short taus); B and the process's
// parameters are maximised over, Tc profiled on a log grid. The three
// hypotheses are compared by -2 ln L + penalty x (the process's parameters:
// 0, 1 for K, 2 for sigma and Tc). The Gauss-Markov parameters get
// profile-likelihood 95 % intervals (-2 ln L within 3.84 of its minimum:
// Tc's from the profile, sigma's as the projection of the joint region),
// infinite where the data do not close them.
#pragma once

#include <span>

#include "foglab/model/noise_fit.h"

namespace foglab::model {

struct RandomBiasOptions {
  /// Block means the likelihood works on (fewer when the record is short).
  int blocks = 256;
  /// Cost of one parameter of the random-bias process (set by the
  /// simulation study in docs/validation.md).
  double penalty = 2.0;
};

struct RandomBiasHypothesis {
  bool fitted = false;
  NoiseModel model;          ///< N from the Allan fit; B and the process by likelihood
  double neg2_loglik = 0.0;  ///< -2 ln L (restricted, up to a shared constant)
  double criterion = 0.0;    ///< neg2_loglik + penalty * parameters
  int parameters = 0;        ///< of the process: 0, 1 (K) or 2 (sigma, Tc)
};

struct RandomBiasLikelihood {
  bool available = false;  ///< false when the record is too short for it
  RandomBiasProcess process = RandomBiasProcess::none;
  RandomBiasHypothesis none, wiener, gauss_markov;
  int blocks = 0;
  double block_s = 0.0;  ///< [s] tau_b
  /// The Gauss-Markov pair of that hypothesis with profile 95 % intervals
  /// (status resolved; infinite ends where the data do not close them).
  ParameterEstimate gm_sigma, gm_tc;
};

/// Decides the random-bias process of a residual rate record [deg/h]
/// sampled at `sample_rate_hz`. `temperature_c` and `degree` (with its
/// reference `t_ref_c`) describe the polynomial removed from it (degree 0 or
/// an empty span: only the mean); `allan_fit` gives N (and the starting
/// values).
RandomBiasLikelihood decide_random_bias(std::span<const double> residual_deg_h,
                                        std::span<const double> temperature_c, int degree,
                                        double t_ref_c, double sample_rate_hz,
                                        const NoiseModel& allan_fit,
                                        const RandomBiasOptions& options = {});

}  // namespace foglab::model
