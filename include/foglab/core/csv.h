// foglab — the cells of the CSV files foglab writes (the Allan tables, the
// lab-2 table, the fleet summary), after RFC 4180.
#pragma once

#include <string>
#include <string_view>

namespace foglab {

/// A number as a CSV cell: 10 significant digits, empty when not finite.
std::string csv_number(double value);

/// A text cell: as it is, or quoted with its quotes doubled when it holds a
/// comma, a quote or a line break.
std::string csv_field(std::string_view text);

}  // namespace foglab
