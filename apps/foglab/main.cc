// foglab — command-line tool for fiber-optic gyroscope signals.
// Exit codes (docs/cli.md): 0 ok, 1 internal error, 2 usage, 3 bad input data.
#include <malloc.h>
#include <sys/resource.h>

#include "app.h"
#include "foglab/core/output.h"

int main(int argc, char** argv) {
  // First, before any thread starts: an interrupted run removes its
  // unfinished outputs (docs/guarantees.md).
  foglab::remove_temporaries_on_interrupt();
  // Under an address-space limit (`ulimit -v`), glibc's per-thread malloc
  // arenas (64 MiB of address space each) run out long before memory
  // does: lab2's threads failed to start under 500 MB. Two arenas suffice.
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    ::mallopt(M_ARENA_MAX, 2);
  }
  return foglab::cli::run_command_line(argc, argv);
}
