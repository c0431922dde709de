// foglab — covariance of overlapping Allan variance estimates across tau
// (internal to the model module: the noise fit's sandwich covariance).
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <span>

#include "foglab/model/noise_fit.h"

namespace foglab::model::detail {

/// Covariance [(deg/h)^4] of the overlapping Allan variance estimates at the
/// averaging factors `m` (tau = m tau0) of a record of `phase_points` angle
/// samples taken every `tau0_s` seconds, for a Gaussian process with the
/// terms of `model`. The rate ramp R, a deterministic trend, adds nothing.
Eigen::MatrixXd allan_variance_covariance(const NoiseModel& model, double tau0_s,
                                          std::span<const std::int64_t> m,
                                          std::int64_t phase_points);

/// The same for estimates pooled over contiguous stretches of
/// `segment_points` angle samples each (core/gaps.h): stretch s contributes
/// n_s(p) = N_s - 2p of the n(p) terms at factor p, the stretches are
/// independent, so Cov(p, q) = sum_s n_s(p) n_s(q) / (n(p) n(q)) Cov_s(p, q)
/// (exact for white, quantisation and random-walk noise, whose Allan terms
/// in disjoint stretches are independent; nearly so for flicker and
/// Gauss-Markov). Costs one covariance per distinct stretch length.
Eigen::MatrixXd pooled_allan_variance_covariance(const NoiseModel& model, double tau0_s,
                                                 std::span<const std::int64_t> m,
                                                 std::span<const std::int64_t> segment_points);

}  // namespace foglab::model::detail
