// foglab — temperature profiles of a synthetic run (error_model.h).
#include "foglab/sim/error_model.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>
#include <vector>

#include "foglab/core/error.h"

namespace foglab::sim {

std::string_view to_string(TemperatureKind kind) {
  switch (kind) {
    case TemperatureKind::constant:
      return "constant";
    case TemperatureKind::ramp:
      return "ramp";
    case TemperatureKind::file:
      return "file";
  }
  return "constant";
}

namespace {

// Whole-string decimal number, or false.
bool parse_number(std::string_view text, double& value) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) {
    text.remove_suffix(1);
  }
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}

[[noreturn]] void bad_syntax(const std::string& text) {
  throw UsageError(fmt::format(
      "temperature profile: expected 'const', 'const:T', 'ramp:SPAN', 'ramp:SPAN@START' "
      "(degC) or 'file:PATH', got '{}'",
      text));
}

// A profile is a short table; a larger file (or /dev/zero) is refused
// before memory runs out.
constexpr std::size_t kMaxProfileBytes = std::size_t{64} << 20;

std::string read_bounded(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DataError(fmt::format("{}: cannot open the temperature profile", path));
  std::string text(kMaxProfileBytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (const auto nul = text.find('\0'); nul != std::string::npos) {
    throw DataError(
        fmt::format("{}: byte {} of the temperature profile is a NUL: binary data, "
                    "not a text table of (time_s, temperature_c) rows",
                    path, nul + 1));
  }
  if (text.size() > kMaxProfileBytes) {
    throw DataError(
        fmt::format("{}: the temperature profile is larger than {} MiB: not a "
                    "table of (time_s, temperature_c) rows",
                    path, kMaxProfileBytes >> 20));
  }
  return text;
}

std::string_view shortened(std::string_view text) {
  return text.size() <= 60 ? text : text.substr(0, 60);
}

TemperatureProfile read_profile_file(const std::string& path) {
  const std::string text = read_bounded(path);
  TemperatureProfile profile;
  profile.kind = TemperatureKind::file;
  int line_number = 0;
  for (std::size_t begin = 0; begin < text.size();) {
    const std::size_t end = std::min(text.find('\n', begin), text.size());
    const std::string_view line(text.data() + begin, end - begin);
    begin = end + 1;
    ++line_number;
    std::string_view body(line);
    if (const auto hash = body.find('#'); hash != std::string_view::npos) body = body.substr(0, hash);
    // Fields separated by white space, commas or semicolons.
    std::vector<std::string_view> fields;
    std::size_t i = 0;
    while (i < body.size()) {
      while (i < body.size() && std::string_view(" \t\r,;").find(body[i]) != std::string_view::npos) ++i;
      const std::size_t start = i;
      while (i < body.size() && std::string_view(" \t\r,;").find(body[i]) == std::string_view::npos) ++i;
      if (i > start) fields.push_back(body.substr(start, i - start));
    }
    if (fields.empty()) continue;
    double t = 0.0;
    double temp = 0.0;
    if (fields.size() != 2 || !parse_number(fields[0], t) || !parse_number(fields[1], temp)) {
      throw DataError(
          fmt::format("{}:{}: expected two finite numbers 'time_s temperature_c', got '{}'", path,
                      line_number, shortened(line)));
    }
    if (!profile.profile_time_s.empty() && !(t > profile.profile_time_s.back())) {
      throw DataError(fmt::format("{}:{}: time {} s is not after the previous time {} s", path,
                                  line_number, t, profile.profile_time_s.back()));
    }
    profile.profile_time_s.push_back(t);
    profile.profile_temperature_c.push_back(temp);
  }
  if (profile.profile_time_s.empty()) {
    throw DataError(fmt::format("{}: no (time_s, temperature_c) rows in the temperature profile",
                                path));
  }
  profile.start_c = profile.profile_temperature_c.front();
  return profile;
}

}  // namespace

double TemperatureProfile::reference_c(double duration_s) const {
  switch (kind) {
    case TemperatureKind::constant:
      return start_c;
    case TemperatureKind::ramp:
      return start_c + 0.5 * span_c;
    case TemperatureKind::file: {
      const auto& t = profile_time_s;
      const auto& y = profile_temperature_c;
      if (t.empty() || t.size() != y.size()) return start_c;
      if (!(duration_s > 0.0)) return y.front();
      // Time-weighted mean over [0, duration] of the piecewise-linear profile,
      // held constant beyond its ends.
      const auto value_at = [&](double time) {
        if (time <= t.front()) return y.front();
        if (time >= t.back()) return y.back();
        const auto hi = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), time) - t.begin());
        const std::size_t lo = hi - 1;
        return y[lo] + (y[hi] - y[lo]) * (time - t[lo]) / (t[hi] - t[lo]);
      };
      // Break points: 0, every profile time inside (0, duration), duration.
      std::vector<double> points{0.0};
      for (const double ti : t) {
        if (ti > 0.0 && ti < duration_s) points.push_back(ti);
      }
      points.push_back(duration_s);
      double integral = 0.0;
      for (std::size_t i = 0; i + 1 < points.size(); ++i) {
        integral += 0.5 * (value_at(points[i]) + value_at(points[i + 1])) * (points[i + 1] - points[i]);
      }
      return integral / duration_s;
    }
  }
  return start_c;
}

TemperatureProfile parse_temperature(const std::string& text) {
  TemperatureProfile profile;
  const std::string_view view(text);
  const auto colon = view.find(':');
  const std::string_view head = view.substr(0, colon);
  const std::string_view arg = colon == std::string_view::npos ? std::string_view() : view.substr(colon + 1);
  if (head == "const") {
    profile.kind = TemperatureKind::constant;
    if (colon != std::string_view::npos && !parse_number(arg, profile.start_c)) bad_syntax(text);
    return profile;
  }
  if (head == "ramp" && colon != std::string_view::npos) {
    profile.kind = TemperatureKind::ramp;
    const auto at = arg.find('@');
    if (!parse_number(arg.substr(0, at), profile.span_c)) bad_syntax(text);
    if (at != std::string_view::npos && !parse_number(arg.substr(at + 1), profile.start_c)) {
      bad_syntax(text);
    }
    return profile;
  }
  if (head == "file" && colon != std::string_view::npos && !arg.empty()) {
    return read_profile_file(std::string(arg));
  }
  bad_syntax(text);
}

}  // namespace foglab::sim
