// foglab — the cells of the CSV files foglab writes (csv.h).
#include "foglab/core/csv.h"

#include <fmt/format.h>

#include <cmath>

namespace foglab {

std::string csv_number(double value) {
  return std::isfinite(value) ? fmt::format("{:.10g}", value) : "";
}

std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\n\r") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (const char ch : text) {
    if (ch == '"') out += '"';
    out += ch;
  }
  return out + "\"";
}

}  // namespace foglab
