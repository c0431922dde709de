// foglab — command-line tool for fiber-optic gyroscope signals.
// Exit codes (docs/cli.md): 0 ok, 1 internal error, 2 usage, 3 bad input data.
#include "app.h"

int main(int argc, char** argv) { return foglab::cli::run_command_line(argc, argv); }
