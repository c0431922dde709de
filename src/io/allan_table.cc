#include "foglab/io/allan_table.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <string_view>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/core/text.h"
#include "readers_internal.h"

namespace foglab::io {
namespace {

using internal::throw_data_error;

// The line's fields, split at commas, semicolons, tabs or runs of spaces.
std::vector<std::string> fields_of(std::string_view line) {
  std::vector<std::string> out;
  std::string field;
  const bool has_separator = line.find_first_of(",;\t") != std::string_view::npos;
  for (const char c : line) {
    const bool separator = has_separator ? (c == ',' || c == ';' || c == '\t') : c == ' ';
    if (separator) {
      if (has_separator || !field.empty()) out.push_back(field);
      field.clear();
    } else if (c != '\r' && !(has_separator && c == ' ' && field.empty())) {
      field += c;
    }
  }
  if (!field.empty() || has_separator) out.push_back(field);
  for (std::string& f : out) {
    while (!f.empty() && f.back() == ' ') f.pop_back();
  }
  return out;
}

std::optional<double> number_of(const std::string& text) {
  double v = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return v;
}

enum class Column { none, tau, dev, other_statistic, n, m, alpha, edf, low, high };

// Statistics whose tau dependence differs from the Allan variance's for
// some noise type (MVAR = AVAR / 2 for white FM, HVAR = AVAR / 2 for
// random-walk FM, TDEV in angle units), so the model's Allan variance cannot
// be fitted to them.
constexpr std::string_view kOtherStatistics[] = {
    "mdev", "tdev", "hdev", "ohdev", "mtotdev", "ttotdev", "htotdev", "theo", "dev_deg_h_s"};

// What a header name means; deviation names carry units as a suffix
// (dev_deg_h, ci68_low_deg_h_s).
Column column_of(const std::string& raw) {
  const std::string name = ascii_lower(raw);
  auto starts = [&](std::string_view p) { return name.rfind(p, 0) == 0; };
  if (name == "tau" || starts("tau_s") || starts("tau [") || starts("tau(") || name == "t") {
    return Column::tau;
  }
  if (name == "n" || name == "#" || name == "count" || name == "terms") return Column::n;
  if (name == "m" || name == "af") return Column::m;
  if (name == "alpha") return Column::alpha;
  if (name == "edf") return Column::edf;
  if (starts("ci68_low") || starts("min sigma") || starts("min_sigma") || name == "low") {
    return Column::low;
  }
  if (starts("ci68_high") || starts("max sigma") || starts("max_sigma") || name == "high") {
    return Column::high;
  }
  if (starts("ci95")) return Column::none;
  for (const std::string_view p : kOtherStatistics) {
    if (starts(p)) return Column::other_statistic;
  }
  for (const std::string_view p :
       {"dev", "adev", "oadev", "totdev", "sigma", "allan", "deviation"}) {
    if (starts(p)) return Column::dev;
  }
  return Column::none;
}

}  // namespace

AllanTable read_allan_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw_data_error(path, "cannot be opened for reading");
  AllanTable t;
  std::vector<Column> columns;
  std::string line;
  int line_number = 0;
  bool any_n = false, any_bounds = false;
  while (std::getline(in, line)) {
    ++line_number;
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    if (line[first] == '#') {
      // Stable32 names its statistic in a comment: "# Sigma Type: Modified Allan".
      const std::size_t type = line.find("Sigma Type:");
      if (type != std::string::npos) {
        const std::string name = line.substr(type + 11);
        const bool allan =
            name.find("Allan") != std::string::npos && name.find("Modified") == std::string::npos;
        if (!allan && name.find(" Total") != 0) {
          throw_data_error(path, fmt::format("line {}: a table of{}: the noise model is fitted "
                                             "to Allan deviations (ADEV, OADEV, TOTDEV)",
                                             line_number, name));
        }
      }
      continue;
    }
    const std::vector<std::string> fields = fields_of(line.substr(first));
    std::vector<std::optional<double>> values;
    bool numeric = true;
    for (const std::string& f : fields) {
      values.push_back(number_of(f));
      numeric = numeric && (values.back().has_value() || f.empty());
    }
    if (columns.empty()) {
      if (!numeric) {  // the header
        for (const std::string& f : fields) columns.push_back(column_of(f));
        const auto other = std::find(columns.begin(), columns.end(), Column::other_statistic);
        if (other != columns.end()) {
          throw_data_error(
              path,
              fmt::format("line {}: the column '{}' is not an Allan deviation: the noise "
                          "model is fitted to ADEV, OADEV or TOTDEV (MDEV, TDEV, the "
                          "Hadamard and the other total deviations follow other laws)",
                          line_number, fields[static_cast<std::size_t>(other - columns.begin())]));
        }
        if (std::count(columns.begin(), columns.end(), Column::tau) != 1 ||
            std::count(columns.begin(), columns.end(), Column::dev) != 1) {
          throw_data_error(path, fmt::format("line {}: the header '{}' names no tau column and "
                                             "one deviation column (e.g. 'tau_s,adev' or "
                                             "the header of foglab's CSV Allan table)",
                                             line_number, line.substr(first)));
        }
        t.layout = "header";
        continue;
      }
      if (fields.size() != 7) {
        throw_data_error(path, fmt::format("line {}: {} numbers and no header line: expected "
                                           "Stable32's seven columns (AF, tau, count, alpha, "
                                           "min sigma, sigma, max sigma) or a header naming them",
                                           line_number, fields.size()));
      }
      columns = {Column::m,   Column::tau, Column::n,   Column::alpha,
                 Column::low, Column::dev, Column::high};
      t.layout = "stable32";
    }
    if (!numeric || fields.size() != columns.size()) {
      throw_data_error(
          path, fmt::format("line {}: expected {} numbers, as the {} says, not '{}'", line_number,
                            columns.size(), t.layout == "header" ? "header" : "first row",
                            line.substr(first)));
    }
    double tau = kNaN, dev = kNaN, low = kNaN, high = kNaN, edf = kNaN;
    std::int64_t n = -1, m = -1;
    int alpha = 0;
    for (std::size_t k = 0; k < columns.size(); ++k) {
      if (!values[k]) continue;
      const double v = *values[k];
      switch (columns[k]) {
        case Column::tau:
          tau = v;
          break;
        case Column::dev:
          dev = v;
          break;
        case Column::n:
          n = std::llround(v);
          break;
        case Column::m:
          m = std::llround(v);
          break;
        case Column::alpha:
          alpha = static_cast<int>(std::lround(v));
          break;
        case Column::edf:
          edf = v;
          break;
        case Column::low:
          low = v > 0.0 ? v : kNaN;
          break;
        case Column::high:
          high = v > 0.0 ? v : kNaN;
          break;
        case Column::none:
        case Column::other_statistic:
          break;
      }
    }
    if (!(tau > 0.0) || !std::isfinite(tau)) {
      throw_data_error(path, fmt::format("line {}: tau {} s is not positive", line_number, tau));
    }
    if (!t.tau_s.empty() && !(tau > t.tau_s.back())) {
      throw_data_error(path, fmt::format("line {}: tau {} s does not follow {} s: taus must "
                                         "increase",
                                         line_number, tau, t.tau_s.back()));
    }
    if (!(dev > 0.0) || !std::isfinite(dev)) {
      throw_data_error(path,
                       fmt::format("line {}: the deviation {} is not positive", line_number, dev));
    }
    t.tau_s.push_back(tau);
    t.dev.push_back(dev);
    t.n.push_back(n);
    t.m.push_back(m);
    t.alpha.push_back(alpha);
    t.edf.push_back(edf);
    t.ci68_low.push_back(low);
    t.ci68_high.push_back(high);
    any_n = any_n || n > 0;
    any_bounds = any_bounds || (std::isfinite(low) && std::isfinite(high));
  }
  if (t.tau_s.size() < 3) {
    throw_data_error(path, fmt::format("{} rows of tau and deviation: the model needs at least 3",
                                       t.tau_s.size()));
  }
  auto has = [&](Column c) {
    return std::find(columns.begin(), columns.end(), c) != columns.end();
  };
  if (!has(Column::n) || !any_n) t.n.clear();
  if (!has(Column::m)) t.m.clear();
  if (!has(Column::alpha)) t.alpha.clear();
  if (!has(Column::edf) ||
      std::none_of(t.edf.begin(), t.edf.end(), [](double e) { return e > 0.0; })) {
    t.edf.clear();
  }
  if (!any_bounds) {
    t.ci68_low.clear();
    t.ci68_high.clear();
  }
  return t;
}

}  // namespace foglab::io
