#include "foglab/core/output.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <optional>
#include <system_error>
#include <thread>
#include <vector>

#include "foglab/core/error.h"

namespace foglab {

void cannot_write(const std::string& path, const std::string& reason) {
  throw UsageError(fmt::format("cannot write '{}': {}", path, reason));
}

void write_failed(const std::string& path, int error_number) {
  std::string_view meaning;
  switch (error_number) {
    case ENOSPC:
    case EDQUOT:
      meaning = "the disk or the user's quota is full";
      break;
    case EFBIG:
      meaning = "the file would exceed the size limit (ulimit -f)";
      break;
    case EPIPE:
      meaning = "the program reading it went away";
      break;
    case EBADF:
      meaning = "the stream is closed";
      break;
    case EIO:
      meaning = "the device reported an I/O error";
      break;
    default:
      cannot_write(path, std::strerror(error_number));
  }
  throw DataError(fmt::format("cannot write '{}': {}: {}; the output is not written", path,
                              std::strerror(error_number), meaning));
}

namespace {

namespace fs = std::filesystem;

// ---- the temporaries of this process ----------------------------------

// Leaked on purpose: the interrupt thread may use it while static objects
// are destroyed at exit.
struct Temporaries {
  std::mutex mutex;  // held while a temporary is put in place
  std::vector<std::string> paths;
};

Temporaries& temporaries() {
  static Temporaries* const t = new Temporaries;
  return *t;
}

// With the mutex held.
void forget(Temporaries& t, const std::string& path) {
  const auto it = std::find(t.paths.begin(), t.paths.end(), path);
  if (it != t.paths.end()) t.paths.erase(it);
}

// Whether `st` is the file our standard output is (device and inode).
bool is_standard_output(const struct stat& st) {
  struct stat out {};
  return ::fstat(STDOUT_FILENO, &out) == 0 && out.st_dev == st.st_dev && out.st_ino == st.st_ino;
}

// Writes all of `data` to `fd`, retrying on EINTR; false with errno set on
// failure.
bool write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

// A regular file behind /dev/stdout (the shell's redirection) is appended
// to, as the shell's own descriptor would write.
int open_in_place(const OutputTarget& t) {
  struct stat st {};
  const bool regular = ::stat(t.file.c_str(), &st) == 0 && S_ISREG(st.st_mode);
  const int fd = ::open(t.file.c_str(), O_WRONLY | O_CLOEXEC | (regular ? O_APPEND : 0));
  if (fd < 0) cannot_write(t.path, std::strerror(errno));
  return fd;
}

namespace {

// The identity of an existing file (links followed), if it exists.
struct Identity {
  bool exists = false;
  dev_t device = 0;
  ino_t inode = 0;
  bool character_device = false;
  bool standard_output = false;  // the file our standard output is
  std::string normal;  // absolute, normal path (links resolved where they exist)
};

Identity identity_of(const std::string& path) {
  Identity id;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    id.exists = true;
    id.device = st.st_dev;
    id.inode = st.st_ino;
    id.character_device = S_ISCHR(st.st_mode);
    id.standard_output = is_standard_output(st);
  }
  std::error_code ec;
  const fs::path normal = fs::weakly_canonical(fs::absolute(path, ec), ec);
  id.normal = ec ? path : normal.string();
  return id;
}

bool same_file(const Identity& a, const Identity& b) {
  if (a.exists && b.exists) return a.device == b.device && a.inode == b.inode;
  return a.normal == b.normal;
}

}  // namespace

std::string OutputTarget::temporary() const {
  const std::string name = fmt::format(".{}.tmp{}", fs::path(file).filename().string(), ::getpid());
  const std::string temporary = special ? (fs::temp_directory_path() / ("foglab" + name)).string()
                                        : (fs::path(file).parent_path() / name).string();
  register_temporary(temporary);
  return temporary;
}

OutputTarget output_target(const std::string& path) {
  OutputTarget t;
  t.path = path;
  if (path.empty()) cannot_write(path, "an empty file name");
  if (path == "-") {
    t.standard_output = true;
    t.file = path;
    return t;
  }
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {  // it exists (links followed)
    if (S_ISDIR(st.st_mode)) cannot_write(path, "it is a directory");
    // Our own standard output under another name (/dev/stdout, the file
    // the shell redirected it to): written through it, in order with the
    // rest of what goes there, not through a second descriptor.
    if (is_standard_output(st)) {
      t.standard_output = true;
      t.file = path;
      return t;
    }
    // /dev/stderr, /dev/fd/N and /proc/PID/fd/N lead through the kernel's
    // own links to whatever the descriptor is (a pipe has no path at all),
    // and even a redirected regular file there is the shell's to keep:
    // written in place.
    std::error_code ec;
    const std::string absolute = fs::absolute(path, ec).lexically_normal().string();
    const bool descriptor =
        absolute == "/dev/stdout" || absolute == "/dev/stderr" ||
        absolute.starts_with("/dev/fd/") ||
        (absolute.starts_with("/proc/") && absolute.find("/fd/") != std::string::npos);
    t.special = !S_ISREG(st.st_mode) || descriptor;
    t.file = t.special ? path : fs::canonical(path, ec).string();
    if (ec) t.file = path;
    return t;
  }
  // Not there yet: follow a dangling link to the file it would create.
  fs::path file(path);
  std::error_code ec;
  for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(file, ec)); ++hops) {
    const fs::path next = fs::read_symlink(file, ec);
    if (ec) break;
    file = next.is_absolute() ? next : file.parent_path() / next;
  }
  t.file = file.string();
  if (fs::path(t.file).filename().empty()) cannot_write(path, "not a file name");
  return t;
}

void commit_temporary(const OutputTarget& t, const std::string& temporary) {
  if (!t.special) {
    int err = 0;
    {
      Temporaries& all = temporaries();
      const std::lock_guard lock(all.mutex);  // an interruption waits for the rename
      if (::rename(temporary.c_str(), t.file.c_str()) == 0) {
        forget(all, temporary);
        return;
      }
      err = errno;
    }
    discard_temporary(temporary);
    write_failed(t.path, err);
  }
  const int in = ::open(temporary.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) {
    const int err = errno;
    discard_temporary(temporary);
    write_failed(t.path, err);
  }
  int out = -1;
  try {
    out = open_in_place(t);
  } catch (...) {
    ::close(in);
    discard_temporary(temporary);
    throw;
  }
  std::vector<char> buffer(1 << 20);
  bool ok = true;
  int err = 0;
  for (;;) {
    const ssize_t n = ::read(in, buffer.data(), buffer.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n < 0) ok = false, err = errno;
      break;
    }
    if (!write_all(out, buffer.data(), static_cast<std::size_t>(n))) {
      ok = false, err = errno;
      break;
    }
  }
  ::close(in);
  if (::close(out) != 0 && ok) ok = false, err = errno;
  discard_temporary(temporary);
  if (!ok) write_failed(t.path, err);
}

void write_text_file(const std::string& path, std::string_view content) {
  const OutputTarget t = output_target(path);
  if (t.standard_output) {
    std::cout << content;
    finish_standard_output();
    return;
  }
  if (t.special) {
    const int fd = open_in_place(t);
    const bool ok = write_all(fd, content.data(), content.size());
    const int err = errno;
    if (::close(fd) != 0 || !ok) write_failed(path, ok ? errno : err);
    return;
  }
  const std::string tmp = t.temporary();
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) {
    const int err = errno;
    discard_temporary(tmp);
    write_failed(path, err);
  }
  const bool ok = write_all(fd, content.data(), content.size());
  const int err = errno;
  const bool closed = ::close(fd) == 0;
  if (!ok || !closed) {
    const int reason = ok ? errno : err;
    discard_temporary(tmp);
    write_failed(path, reason);
  }
  commit_temporary(t, tmp);
}

void check_outputs(std::span<const RunPath> inputs, std::span<const RunPath> outputs) {
  std::vector<std::pair<const RunPath*, Identity>> seen;
  const RunPath* standard_output = nullptr;
  for (const RunPath& in : inputs) {
    if (in.path.empty() || in.path == "-") continue;
    seen.emplace_back(&in, identity_of(in.path));
  }
  const std::size_t input_count = seen.size();
  for (const RunPath& out : outputs) {
    if (out.path.empty()) continue;
    const Identity id = identity_of(out.path);
    if (out.path == "-" || (id.standard_output && !id.character_device)) {
      if (standard_output != nullptr) {
        throw UsageError(fmt::format(
            "{} {} and {} {}: only one output can go to standard output (the two would be "
            "run together and neither readable); give one of them a file name",
            standard_output->option, standard_output->path, out.option, out.path));
      }
      standard_output = &out;
      continue;
    }
    for (std::size_t k = 0; k < seen.size(); ++k) {
      const auto& [other, other_id] = seen[k];
      if (!same_file(id, other_id) || (id.exists && id.character_device)) continue;
      if (k < input_count) {
        throw UsageError(fmt::format(
            "{} '{}' is the input {} '{}': writing it would destroy the recording; give the "
            "output another name",
            out.option, out.path, other->option, other->path));
      }
      throw UsageError(fmt::format(
          "{} '{}' and {} '{}' are the same file: one output would replace the other; give "
          "them different names",
          other->option, other->path, out.option, out.path));
    }
    seen.emplace_back(&out, id);
  }
}

void finish_standard_output() {
  std::cout.flush();
  const bool lost = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout) != 0;
  if (lost) {
    throw DataError(
        fmt::format("cannot write to standard output ({}): what was printed there is lost",
                    errno != 0 ? std::strerror(errno) : "the stream failed"));
  }
}

void register_temporary(const std::string& path) {
  Temporaries& all = temporaries();
  const std::lock_guard lock(all.mutex);
  all.paths.push_back(path);
}

void discard_temporary(const std::string& path) {
  Temporaries& all = temporaries();
  const std::lock_guard lock(all.mutex);
  std::error_code ec;
  fs::remove_all(path, ec);
  forget(all, path);
}

void remove_temporaries_on_interrupt() {
  std::signal(SIGXFSZ, SIG_IGN);
  std::signal(SIGPIPE, SIG_IGN);
  sigset_t stops;
  sigemptyset(&stops);
  for (const int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&stops, s);
  // Blocked here, before any other thread exists, so every thread inherits
  // the mask and only the one below takes these signals — as ordinary
  // code, free to take the lock and remove folders.
  pthread_sigmask(SIG_BLOCK, &stops, nullptr);
  auto take_signals = [stops] {
    int signal_number = 0;
    while (sigwait(&stops, &signal_number) != 0) {
    }
    Temporaries& all = temporaries();
    all.mutex.lock();  // held to the end: nothing new is put in place
    std::size_t removed = 0;
    for (const std::string& path : all.paths) {
      std::error_code ec;
      if (fs::remove_all(path, ec) > 0) ++removed;
    }
    const char* name = sigabbrev_np(signal_number);
    const std::string message =
        removed == 0
            ? fmt::format("foglab: interrupted (SIG{}): stopped; no output was being written\n",
                          name != nullptr ? name : "?")
            : fmt::format(
                  "foglab: interrupted (SIG{}): stopped; {} unfinished output{} removed, "
                  "earlier files kept\n",
                  name != nullptr ? name : "?", removed, removed == 1 ? "" : "s");
    [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, message.data(), message.size());
    ::_exit(128 + signal_number);
  };
  try {
    std::thread(take_signals).detach();
  } catch (const std::system_error&) {
    // No thread to spare (`ulimit -v` near nothing): the signals keep
    // their default action, and the run goes on to its own out-of-memory
    // message.
    pthread_sigmask(SIG_UNBLOCK, &stops, nullptr);
  }
}

// ---- folders ----------------------------------------------------------

OutputFolder::OutputFolder(std::string option, const std::string& path)
    : option_(std::move(option)), path_(path) {
  auto refuse = [&](const std::string& reason) {
    throw UsageError(fmt::format("{} '{}': {}", option_, path_, reason));
  };
  if (path.empty()) refuse("an empty folder name");
  std::error_code ec;
  fs::path target = fs::absolute(path, ec).lexically_normal();
  if (!target.has_filename()) target = target.parent_path();  // "out/"
  const fs::file_status status = fs::status(target, ec);      // links followed
  const bool exists = fs::exists(status);
  if (exists && !fs::is_directory(status)) refuse("a file of that name exists; give a folder");
  if (exists) target = fs::canonical(target, ec);
  target_ = target.string();
  // An existing folder holds its own temporary (its parent may not be
  // ours to write: '--out .' at home); a new one is made beside it.
  const fs::path parent = exists ? target : target.parent_path();
  if (!exists) {
    fs::create_directories(parent, ec);
    if (ec) refuse("cannot create the folder: " + ec.message());
  }
  const std::string name = exists
                               ? fmt::format(".foglab.tmp{}", ::getpid())
                               : fmt::format(".{}.tmp{}", target.filename().string(), ::getpid());
  temporary_ = (parent / name).string();
  register_temporary(temporary_);
  fs::remove_all(temporary_, ec);
  if (!fs::create_directory(temporary_, ec) || ec) {
    const std::string reason = ec ? ec.message() : "it exists";
    discard_temporary(temporary_);
    temporary_.clear();
    refuse(fmt::format("cannot create the folder: {}", reason));
  }
}

OutputFolder::~OutputFolder() {
  if (!temporary_.empty()) discard_temporary(temporary_);
}

std::string OutputFolder::file(std::string_view name) const {
  return (fs::path(temporary_) / name).string();
}

std::string OutputFolder::final_file(std::string_view name) const {
  return (fs::path(path_) / name).string();
}

void OutputFolder::commit() {
  Temporaries& all = temporaries();
  std::error_code ec;
  {
    const std::lock_guard lock(all.mutex);  // an interruption waits for the whole move
    if (!fs::exists(target_, ec) && ::rename(temporary_.c_str(), target_.c_str()) == 0) {
      forget(all, temporary_);
      temporary_.clear();
      return;
    }
    // The target exists: every file is moved over its old version, after
    // checking that none would land on a folder.
    std::vector<fs::path> names;
    for (const fs::directory_entry& e : fs::directory_iterator(temporary_, ec)) {
      names.push_back(e.path().filename());
    }
    std::string reason = ec ? ec.message() : "";
    for (const fs::path& n : names) {
      if (reason.empty() && fs::is_directory(fs::path(target_) / n, ec)) {
        reason = fmt::format("'{}' there is a folder", n.string());
      }
    }
    std::size_t moved = 0;
    for (; reason.empty() && moved < names.size(); ++moved) {
      if (::rename((fs::path(temporary_) / names[moved]).c_str(),
                   (fs::path(target_) / names[moved]).c_str()) != 0) {
        reason = fmt::format("'{}': {}", names[moved].string(), std::strerror(errno));
        break;
      }
    }
    if (reason.empty()) {
      fs::remove_all(temporary_, ec);
      forget(all, temporary_);
      temporary_.clear();
      return;
    }
    if (moved > 0) {
      reason += fmt::format("; {} of the {} files were already replaced", moved, names.size());
    } else {
      reason += "; the folder is as it was";
    }
    throw UsageError(
        fmt::format("{} '{}': cannot put the outputs in place: {}", option_, path_, reason));
  }
}

}  // namespace foglab
