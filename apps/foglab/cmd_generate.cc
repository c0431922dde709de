// placeholder: filled in by the work on issue 3
#include "commands.h"

namespace foglab::cli {
std::function<void()> register_generate(CLI::App& app) {
  app.add_subcommand("generate", "synthetic static-gyro recording with known truth (in progress)");
  return [] {};
}
}  // namespace foglab::cli
