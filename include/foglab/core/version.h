// foglab — version of the library and the tool.
#pragma once

#include <string_view>

namespace foglab {

/// The project version, e.g. "0.1.0".
std::string_view version();

}  // namespace foglab
