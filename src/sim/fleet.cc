#include "foglab/sim/fleet.h"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/special_functions/erf.hpp>
#include <cmath>
#include <numbers>

#include "foglab/core/error.h"
#include "generator_internal.h"

namespace foglab::sim {
namespace {

using detail::mix64;  // SplitMix64 (generator_internal.h)

/// A uniform number in (0, 1), a pure function of its arguments.
double uniform(std::uint64_t seed, std::uint64_t unit, std::uint64_t draw) {
  const std::uint64_t bits = mix64(mix64(mix64(seed) ^ unit) + draw);
  return (static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53;
}

/// A standard normal number: the inverse of the normal distribution function.
double standard_normal(std::uint64_t seed, std::uint64_t unit, std::uint64_t draw) {
  return std::numbers::sqrt2 * boost::math::erf_inv(2.0 * uniform(seed, unit, draw) - 1.0);
}

}  // namespace

std::vector<FleetMember> draw_fleet(const ErrorModel& nominal, const FleetSpec& spec) {
  if (spec.units == 0 || spec.units > 1000000) {
    throw UsageError(fmt::format("a fleet has 1 to 1000000 units, not {}", spec.units));
  }
  if (!(spec.spread_log10 >= 0.0 && spec.spread_log10 <= 2.0)) {
    throw UsageError(fmt::format(
        "the fleet's spread must be from 0 to 2 (sigma of log10 of each coefficient), got {}",
        spec.spread_log10));
  }
  if (spec.outliers > spec.units / 10) {
    throw UsageError(fmt::format(
        "{} outliers in a fleet of {} units: at most a tenth of the units (outliers stand out "
        "of a fleet)",
        spec.outliers, spec.units));
  }
  if (spec.outliers > 0 && !(spec.outlier_factor > 0.0 && std::isfinite(spec.outlier_factor) &&
                             spec.outlier_factor != 1.0)) {
    throw UsageError(
        fmt::format("the outlier factor must be positive and not 1, got {}", spec.outlier_factor));
  }
  // The coefficients that scatter, in a fixed order (a draw index each).
  struct Coefficient {
    const char* name;
    double NoiseModel::*field;
    bool may_stand_out;  // an outlier's term (N, B, K: what batch reports with intervals)
  };
  static constexpr Coefficient kScattered[] = {
      {"N", &NoiseModel::N, true},  {"B", &NoiseModel::B, true},
      {"K", &NoiseModel::K, true},  {"R", &NoiseModel::R, false},
      {"Q", &NoiseModel::Q, false}, {"gm_sigma", &NoiseModel::gm_sigma, false}};
  std::vector<const Coefficient*> outlier_terms;
  for (const Coefficient& c : kScattered) {
    if (c.may_stand_out && nominal.noise.*c.field > 0.0) outlier_terms.push_back(&c);
  }
  if (outlier_terms.empty()) {
    throw UsageError("the fleet's nominal model has none of N, B, K: nothing to scatter");
  }

  std::vector<FleetMember> fleet(spec.units);
  for (std::size_t u = 0; u < spec.units; ++u) {
    fleet[u].model = nominal;
    for (std::size_t k = 0; k < std::size(kScattered); ++k) {
      double& value = fleet[u].model.noise.*kScattered[k].field;
      value *= std::pow(10.0, spec.spread_log10 * standard_normal(spec.seed, u, k));
    }
  }
  // The outliers: distinct units chosen by a partial Fisher-Yates shuffle.
  std::vector<std::size_t> order(spec.units);
  for (std::size_t u = 0; u < spec.units; ++u) order[u] = u;
  for (std::size_t i = 0; i < spec.outliers; ++i) {
    const double draw = uniform(spec.seed, spec.units + i, 1000);
    const std::size_t j =
        i + std::min(spec.units - i - 1, static_cast<std::size_t>(draw * double(spec.units - i)));
    std::swap(order[i], order[j]);
    const Coefficient& term = *outlier_terms[i % outlier_terms.size()];
    FleetMember& member = fleet[order[i]];
    member.model.noise.*term.field *= spec.outlier_factor;
    member.outlier_parameter = term.name;
  }
  return fleet;
}

}  // namespace foglab::sim
