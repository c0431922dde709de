// placeholder: filled in by the work on issue 3
#include "commands.h"

namespace foglab::cli {
std::function<void()> register_lab2_data(CLI::App& app) {
  app.add_subcommand("lab2-data", "the lab-2 variant data sets and answer key (in progress)");
  return [] {};
}
}  // namespace foglab::cli
