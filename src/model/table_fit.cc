#include "foglab/model/table_fit.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "foglab/core/error.h"
#include "foglab/core/noise_model.h"
#include "foglab/core/numeric.h"
#include "foglab/model/readings.h"
#include "foglab/stats/confidence.h"

namespace foglab::model {
namespace {

// SP 1065's white-FM edf of OADEV at factor m on N phase points.
double white_fm_oadev_edf(double n_phase, double m) {
  const double edf = (3.0 * (n_phase - 1.0) / (2.0 * m) - 2.0 * (n_phase - 2.0) / n_phase) *
                     (4.0 * m * m / (4.0 * m * m + 5.0));
  return edf > 0.0 ? edf : kNaN;
}

// Each tau's averaging factor: the table's, else tau / tau_1.
double factor_at(const TableColumns& t, std::size_t k) {
  if (!t.m.empty() && t.m[k] > 0) return static_cast<double>(t.m[k]);
  return std::max(1.0, std::round(t.tau_s[k] / t.tau_s[0]));
}

}  // namespace

std::string_view to_string(TableEdfSource source) {
  switch (source) {
    case TableEdfSource::edf_column:
      return "edf_column";
    case TableEdfSource::bounds:
      return "bounds";
    case TableEdfSource::counts:
      return "counts";
    case TableEdfSource::assumed:
      return "assumed";
  }
  return "?";
}

TableFit fit_allan_table(const TableColumns& table, const NoiseFitOptions& options) {
  const std::size_t count = table.tau_s.size();
  auto sized = [count](std::size_t size) { return size == 0 || size == count; };
  if (table.dev.size() != count || !sized(table.n.size()) || !sized(table.m.size()) ||
      !sized(table.edf.size()) || !sized(table.ci68_low.size()) || !sized(table.ci68_high.size())) {
    throw UsageError("fit_allan_table: the table's columns differ in length");
  }
  if (count < 3) throw UsageError("fit_allan_table: the model needs at least 3 taus");
  TableFit r;
  r.edf.assign(count, kNaN);
  // The first source that gives every point an edf; rows a source misses
  // take the next one's.
  std::size_t from_column = 0, from_bounds = 0, from_counts = 0;
  for (std::size_t k = 0; k < count; ++k) {
    if (!table.edf.empty() && table.edf[k] > 0.0) {
      r.edf[k] = table.edf[k];
      ++from_column;
    } else if (!table.ci68_low.empty()) {
      r.edf[k] = stats::edf_from_interval(table.dev[k], table.ci68_low[k], table.ci68_high[k],
                                          stats::kConfidence68);
      if (std::isfinite(r.edf[k])) ++from_bounds;
    }
    if (!std::isfinite(r.edf[k]) && !table.n.empty() && table.n[k] > 0) {
      const double m = factor_at(table, k);
      r.edf[k] = white_fm_oadev_edf(static_cast<double>(table.n[k]) + 2.0 * m, m);
      if (std::isfinite(r.edf[k])) ++from_counts;
    }
  }
  r.edf_source = from_column > 0   ? TableEdfSource::edf_column
                 : from_bounds > 0 ? TableEdfSource::bounds
                 : from_counts > 0 ? TableEdfSource::counts
                                   : TableEdfSource::assumed;
  const std::size_t given = from_column + from_bounds + from_counts;
  if (given == 0) {
    // A record of 10 times the longest tau, in steps of the first tau.
    const double n_phase = 10.0 * table.tau_s[count - 1] / table.tau_s[0] + 1.0;
    for (std::size_t k = 0; k < count; ++k) {
      r.edf[k] = white_fm_oadev_edf(n_phase, factor_at(table, k));
    }
    r.notes.emplace_back(Text::table_note_no_edf);
  } else if (given < count) {
    r.notes.emplace_back(Text::table_note_some_no_edf, count - given, count);
  }
  if (r.edf_source == TableEdfSource::counts) {
    r.notes.emplace_back(Text::table_note_edf_from_counts);
  }
  std::vector<double> tau, dev, edf;
  for (std::size_t k = 0; k < count; ++k) {
    if (!std::isfinite(r.edf[k])) continue;
    tau.push_back(table.tau_s[k]);
    dev.push_back(table.dev[k]);
    edf.push_back(r.edf[k]);
  }
  r.fit = fit_noise_model(tau, dev, edf, options);
  if (given == 0) {
    for (const NoiseParameter& p : kNoiseParameters) {
      ParameterEstimate& e = r.fit.estimate(p);
      e.ci95_low = e.ci95_high = e.upper_95 = kNaN;
    }
  }
  const AdevReadings readings = read_adev(table.tau_s, table.dev, r.fit.filter_memory_end_tau_s);
  r.bias_instability_deg_h = readings.bias_instability_deg_h;
  r.bias_instability_tau_s = readings.bias_instability_tau_s;
  if (Message note = minimum_inside_filter_note(readings); !note.empty()) {
    r.notes.push_back(std::move(note));
  }
  r.arw_deg_sqrt_h = r.fit.status == FitStatus::degenerate    ? kNaN
                     : r.fit.N.status == TermStatus::resolved ? arw_deg_sqrt_h(r.fit.model.N)
                                                              : arw_deg_sqrt_h(r.fit.N.upper_95);
  r.verdict = classify(r.bias_instability_deg_h, r.arw_deg_sqrt_h);
  return r;
}

}  // namespace foglab::model
