// foglab — small text helpers shared by the readers, the options and the
// reports.
#pragma once

#include <string>
#include <string_view>

namespace foglab {

/// `text` with the ASCII letters A–Z made lower case and every other byte
/// as it is, whatever the C locale: names, units and file extensions are
/// compared with it, and a UTF-8 name (a Russian channel name) stays intact.
std::string ascii_lower(std::string_view text);

}  // namespace foglab
