// foglab — a fleet's statistics (fleet.h explains the choices).
#include "foglab/model/fleet.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"

namespace foglab::model {
namespace {

// The q-quantile of sorted values, by linear interpolation between order statistics.
double quantile(const std::vector<double>& sorted, double q) {
  const double at = q * static_cast<double>(sorted.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(at));
  const std::size_t above = std::min(below + 1, sorted.size() - 1);
  return sorted[below] + (at - static_cast<double>(below)) * (sorted[above] - sorted[below]);
}

bool counts(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

FleetSummary summarize_fleet(const std::vector<FleetUnit>& units,
                             const std::vector<std::string>& parameters,
                             const FleetOptions& options) {
  if (!(options.outlier_z > 0.0) || !std::isfinite(options.outlier_z)) {
    throw UsageError(fmt::format("FleetOptions::outlier_z must be a finite number > 0 (got {})",
                                 options.outlier_z));
  }
  FleetSummary summary;
  summary.units = units.size();
  for (const FleetUnit& u : units) {
    if (!u.accuracy_class.empty()) ++summary.classes[u.accuracy_class];
  }
  // The outliers per unit, each unit's in parameter order.
  std::vector<std::vector<FleetOutlier>> by_unit(units.size());
  for (const std::string& name : parameters) {
    ParameterSpread p;
    p.name = name;
    std::vector<double> logs;
    std::vector<double> values;
    for (const FleetUnit& u : units) {
      const auto it = u.values.find(name);
      if (it != u.values.end() && counts(it->second)) {
        values.push_back(it->second);
        logs.push_back(std::log10(it->second));
      }
    }
    p.units = values.size();
    if (values.size() < 2) {
      p.median = p.spread_log10 = p.spread_factor = p.minimum = p.maximum = p.p05 = p.p95 = kNaN;
      if (values.size() == 1) p.median = p.minimum = p.maximum = values.front();
      summary.parameters.push_back(p);
      continue;
    }
    std::sort(values.begin(), values.end());
    // The median and 1.4826 MAD of log10 (core/numeric.h).
    const RobustSpread log_spread = robust_spread(logs);
    p.median = std::pow(10.0, log_spread.centre);
    p.spread_log10 = log_spread.spread;
    p.spread_factor = std::pow(10.0, p.spread_log10);
    p.minimum = values.front();
    p.maximum = values.back();
    p.p05 = quantile(values, 0.05);
    p.p95 = quantile(values, 0.95);
    summary.parameters.push_back(p);
    if (!(log_spread.spread > 0.0)) continue;
    for (std::size_t k = 0; k < units.size(); ++k) {
      const auto it = units[k].values.find(name);
      if (it == units[k].values.end() || !counts(it->second)) continue;
      // 0.6745 (x - median) / MAD, with 0.6745 = 1 / 1.4826: the distance in robust sigmas.
      const double z = (std::log10(it->second) - log_spread.centre) / log_spread.spread;
      if (!(std::abs(z) > options.outlier_z)) continue;
      // With its interval, beyond the limit only if the whole interval is.
      const auto interval = units[k].ci95.find(name);
      if (interval != units[k].ci95.end()) {
        const double limit = std::pow(
            10.0, log_spread.centre + std::copysign(options.outlier_z, z) * log_spread.spread);
        const double near_end = z > 0 ? interval->second.first : interval->second.second;
        if (std::isnan(near_end) || (z > 0 ? near_end <= limit : near_end >= limit)) continue;
      }
      by_unit[k].push_back({units[k].name, name, it->second, z, it->second / p.median});
    }
  }
  for (auto& list : by_unit) {
    summary.outliers.insert(summary.outliers.end(), list.begin(), list.end());
  }
  return summary;
}

}  // namespace foglab::model
