// Test support: the published reference data sets (NIST SP 1065, Stable32).
#pragma once

#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace foglab::test {

inline std::string data_path(const std::string& relative) {
  return std::string(FOGLAB_TEST_DATA_DIR) + "/" + relative;
}

/// NBS14 1000-point fractional-frequency set (NIST SP 1065 p. 108):
/// n_0 = 1234567890, n_{i+1} = 16807 n_i mod 2147483647, y_i = n_i / 2147483647.
inline std::vector<double> nbs14_1000() {
  std::vector<double> y;
  std::int64_t n = 1234567890;
  for (int i = 0; i < 1000; ++i) {
    y.push_back(static_cast<double>(n) / 2147483647.0);
    n = (16807 * n) % 2147483647;
  }
  return y;
}

/// NBS14 9-point fractional-frequency set (10 phase points).
inline std::vector<double> nbs14_10() { return {892, 809, 823, 798, 671, 644, 883, 903, 677}; }

/// One row of a Stable32 output table.
struct Stable32Row {
  std::int64_t af = 0;
  double tau_s = 0.0;
  std::int64_t n = 0;
  int alpha = 0;
  double min_sigma = 0.0;
  double sigma = 0.0;
  double max_sigma = 0.0;
};

/// The rows of a Stable32 table whose data lines `parse` reads (it returns
/// false for a line that is not a row).
template <typename Parse>
std::vector<Stable32Row> read_stable32_rows(const std::string& file, Parse parse) {
  std::ifstream in(data_path("stable32-phasedat/" + file));
  if (!in) throw std::runtime_error("missing reference file " + file);
  std::vector<Stable32Row> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    Stable32Row r;
    if (parse(fields, r)) rows.push_back(r);
  }
  return rows;
}

/// A table with intervals: AF, tau, count, alpha, min sigma, sigma, max sigma
/// (Theo1's tables print the count as a float, 4.9550e+03).
inline std::vector<Stable32Row> read_stable32(const std::string& file) {
  return read_stable32_rows(file, [](std::istringstream& f, Stable32Row& r) {
    double count = 0.0;
    const bool ok = static_cast<bool>(f >> r.af >> r.tau_s >> count >> r.alpha >> r.min_sigma >>
                                      r.sigma >> r.max_sigma);
    r.n = std::llround(count);
    return ok;
  });
}

/// A Stable32 table without intervals (AF, tau, count, value: MTIE, TIE
/// rms); `sigma` holds the value.
inline std::vector<Stable32Row> read_stable32_values(const std::string& file) {
  return read_stable32_rows(file, [](std::istringstream& f, Stable32Row& r) {
    return static_cast<bool>(f >> r.af >> r.tau_s >> r.n >> r.sigma);
  });
}

/// PHASE.DAT: 1001 phase points, tau0 = 1 s.
inline std::vector<double> phase_dat() {
  std::ifstream in(data_path("stable32-phasedat/PHASE.DAT"));
  std::vector<double> x;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    x.push_back(std::stod(line));
  }
  return x;
}

}  // namespace foglab::test
