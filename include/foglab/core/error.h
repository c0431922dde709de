// foglab — error policy shared by every module.
//
// One policy, written down (see CONTRIBUTING.md):
//   * a bad argument or option value  -> foglab::UsageError (an std::invalid_argument)
//     naming the parameter and the value; the CLI exits with code 2;
//   * bad input data (a file's content) -> foglab::DataError naming the file and
//     the variable, line, column or sample index and what was expected; exit 3;
//   * a numerical outcome (a fit that does not converge) -> a status in the
//     result struct, never an exception;
//   * broken invariants -> assert().
#pragma once

#include <stdexcept>
#include <string>

namespace foglab {

/// A command-line argument or API parameter is invalid. CLI exit code 2.
class UsageError : public std::invalid_argument {
 public:
  explicit UsageError(const std::string& what) : std::invalid_argument(what) {}
};

/// The input data are unusable (empty, non-numeric, NaN, corrupt, too short).
/// The message names the source. CLI exit code 3.
class DataError : public std::runtime_error {
 public:
  explicit DataError(const std::string& what) : std::runtime_error(what) {}
};

/// CLI exit codes (docs/conventions.md section 11).
enum ExitCode : int { kExitOk = 0, kExitInternal = 1, kExitUsage = 2, kExitData = 3 };

}  // namespace foglab
