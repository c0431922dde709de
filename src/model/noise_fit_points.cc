// foglab — noise-model fit, step 1: the points (noise_fit_internal.h).
#include <fmt/format.h>

#include <cmath>

#include "foglab/core/error.h"
#include "foglab/stats/edf.h"
#include "noise_fit_internal.h"

namespace foglab::model::detail {

Points gather_points(std::span<const double> tau_s, std::span<const double> adev_deg_h,
                     std::span<const double> edf, std::span<const std::int64_t> factors,
                     std::span<const std::int64_t> segment_points,
                     std::span<const double> term_share, std::span<const double> edf_reduction,
                     const NoiseFitOptions& options, const DetrendFactors* detrend) {
  if (options.max_iterations < 1) {
    throw UsageError(fmt::format("NoiseFitOptions::max_iterations must be >= 1, got {}",
                                 options.max_iterations));
  }
  if (!(options.tolerance >= 0.0) || !std::isfinite(options.tolerance)) {
    throw UsageError(fmt::format("NoiseFitOptions::tolerance must be finite and >= 0, got {}",
                                 options.tolerance));
  }
  if (detrend && detrend->tau_s.size() != tau_s.size()) {
    throw UsageError(fmt::format("noise-model fit: {} detrending factors for {} tau points",
                                 detrend->tau_s.size(), tau_s.size()));
  }
  if (!term_share.empty() && term_share.size() != tau_s.size()) {
    throw UsageError(fmt::format("noise-model fit: {} term shares for {} tau points",
                                 term_share.size(), tau_s.size()));
  }
  if (!edf_reduction.empty() && edf_reduction.size() != tau_s.size()) {
    throw UsageError(fmt::format("noise-model fit: {} edf reductions for {} tau points",
                                 edf_reduction.size(), tau_s.size()));
  }
  if (tau_s.size() != adev_deg_h.size() || tau_s.size() != edf.size()) {
    throw UsageError(
        fmt::format("noise-model fit: tau, deviation and edf need equal counts, got {}, {} and {}",
                    tau_s.size(), adev_deg_h.size(), edf.size()));
  }
  Points p;
  for (std::size_t i = 0; i < tau_s.size(); ++i) {
    if (!(tau_s[i] > 0) || !(adev_deg_h[i] > 0) || !std::isfinite(adev_deg_h[i])) {
      throw UsageError(
          fmt::format("noise-model fit: point {} has tau {} s and deviation {} deg/h; both must be "
                      "positive and finite",
                      i + 1, tau_s[i], adev_deg_h[i]));
    }
    if (!(edf[i] >= options.min_edf)) continue;
    p.tau.push_back(tau_s[i]);
    p.y.push_back(adev_deg_h[i] * adev_deg_h[i]);
    p.v.push_back(edf[i]);
    p.index.push_back(i);
    if (!factors.empty()) {
      const double share = term_share.empty() ? 1.0 : term_share[i];
      const double reduction = edf_reduction.empty() ? 1.0 : edf_reduction[i];
      std::array<double, 4> e{};
      const int alphas[] = {-2, -1, 0, 2};
      for (int a = 0; a < 4; ++a) {
        e[static_cast<std::size_t>(a)] =
            share * stats::pooled_edf(alphas[a], factors[i], segment_points) / reduction;
      }
      p.edf_by_alpha.push_back(e);
      p.factors.push_back(factors[i]);
      if (!term_share.empty()) p.term_share.push_back(share);
      if (!edf_reduction.empty()) p.edf_reduction.push_back(reduction);
    }
  }
  p.detrend = detrend;
  p.segment_points.assign(segment_points.begin(), segment_points.end());
  p.control = {options.tolerance, options.max_iterations};
  if (p.y.size() < 3) {
    throw UsageError(fmt::format(
        "noise-model fit: {} usable Allan-deviation points (edf >= {}); at least 3 are needed",
        p.y.size(), options.min_edf));
  }
  return p;
}

}  // namespace foglab::model::detail
