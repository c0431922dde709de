// foglab — writing result files without ever leaving a half-written one.
#pragma once

#include <string>
#include <string_view>

namespace foglab {

/// Writes `content` to `path` atomically: the text goes to a temporary file
/// in the same directory, which is renamed over `path` only once it is
/// complete. `path` "-" writes to standard output. Throws UsageError when the
/// directory cannot be written (naming the path and the system's reason).
void write_text_file(const std::string& path, std::string_view content);

}  // namespace foglab
