// foglab — covariance of block means of the noise model's terms (internal to
// the model module: the temperature fit's standard errors and detrending
// factors, and the random-bias likelihood).
#pragma once

#include <cstddef>
#include <vector>

#include "foglab/model/noise_fit.h"

namespace foglab::model::detail {

/// Which terms of a model: those with a finite variance, or the others.
enum class TermGroup {
  stationary,     ///< white, quantisation, Gauss-Markov
  non_stationary  ///< flicker and Wiener
};

/// Covariance of the means of consecutive blocks of `tau` seconds at lags
/// 0..lags-1 [(deg/h)^2] for the terms of `m` in `group`. The non-stationary
/// terms have no variance and are given up to a matrix f(a) + f(b) that any
/// contrast (weights summing to zero) cancels.
std::vector<double> block_covariance(const NoiseModel& m, double tau, std::size_t lags,
                                     TermGroup group);

}  // namespace foglab::model::detail
