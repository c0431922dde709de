// foglab — command-line tool for fiber-optic gyroscope signals.
// Exit codes (docs/cli.md): 0 ok, 1 internal error, 2 usage, 3 bad input data.
#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdlib>
#include <string_view>

#include "app.h"
#include "foglab/core/output.h"

namespace {

// glibc's malloc returns each large block to the system when it is freed and gets fresh
// pages for the next; an analysis allocates and frees its working arrays (10^7 samples each)
// many times, and on virtual machines the first touch of a fresh page costs as much as the
// work done on it (a third of an 8 h IMU bag's analysis went to page faults). glibc's malloc
// tunables change that (the glibc manual, "Memory Allocation Tunables"): large blocks stay
// in the heap and are reused, and the heap gets transparent huge pages. They are read only
// when a process starts, so foglab starts itself again once with them set; measured in
// bench/RESULTS.md (issue 17). Only for the commands that run whole analyses, which allocate
// and free such arrays over and over: a second start costs the others (`allan` on 2e7 samples
// takes 0.2 s) a third of their time (issue 19). Not when GLIBC_TUNABLES is set already (the
// user's choice stands, and it marks the second start), nor under an address-space limit,
// where memory is better returned.
bool runs_whole_analyses(int argc, char** argv) {
  for (int k = 1; k < argc; ++k) {
    const std::string_view word = argv[k];
    if (word == "analyze" || word == "batch" || word == "lab2") return true;
  }
  return false;
}

void restart_with_malloc_tunables(int argc, char** argv) {
#ifdef __linux__
  if (std::getenv("GLIBC_TUNABLES") != nullptr || !runs_whole_analyses(argc, argv)) return;
  if (::setenv("GLIBC_TUNABLES",
               "glibc.malloc.hugetlb=1:glibc.malloc.mmap_max=0:"
               "glibc.malloc.trim_threshold=4294967296",
               0) != 0) {
    return;
  }
  ::execv("/proc/self/exe", argv);
  ::unsetenv("GLIBC_TUNABLES");  // not restarted: on as before
#else
  (void)argc;
  (void)argv;
#endif
}

}  // namespace

int main(int argc, char** argv) {
  // Under an address-space limit (`ulimit -v`), glibc's per-thread malloc
  // arenas (64 MiB of address space each) run out long before memory
  // does: lab2's threads failed to start under 500 MB. And a thread whose
  // arena cannot be made gets every block from mmap and gives it back with
  // munmap, two system calls an allocation: under 150 MB the noise fit ran
  // for minutes instead of a second. One arena, the main heap, shared by
  // every thread, grows to the limit and then fails plainly.
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    ::mallopt(M_ARENA_MAX, 1);
  } else {
    restart_with_malloc_tunables(argc, argv);
  }
  // Before any thread starts: an interrupted run removes its unfinished
  // outputs (docs/guarantees.md).
  foglab::remove_temporaries_on_interrupt();
  return foglab::cli::run_command_line(argc, argv);
}
