#include "foglab/core/output.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <vector>

#include "foglab/core/error.h"

namespace foglab {

void cannot_write(const std::string& path, const std::string& reason) {
  throw UsageError(fmt::format("cannot write '{}': {}", path, reason));
}

namespace {

namespace fs = std::filesystem;

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
  if (special) return (fs::temp_directory_path() / ("foglab" + name)).string();
  return (fs::path(file).parent_path() / name).string();
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
    std::error_code ec;
    fs::rename(temporary, t.file, ec);
    if (ec) {
      std::remove(temporary.c_str());
      cannot_write(t.path, ec.message());
    }
    return;
  }
  const int in = ::open(temporary.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) {
    const int err = errno;
    std::remove(temporary.c_str());
    cannot_write(t.path, std::strerror(err));
  }
  int out = -1;
  try {
    out = open_in_place(t);
  } catch (...) {
    ::close(in);
    std::remove(temporary.c_str());
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
  std::remove(temporary.c_str());
  if (!ok) cannot_write(t.path, std::strerror(err));
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
    if (::close(fd) != 0 || !ok) cannot_write(path, std::strerror(ok ? errno : err));
    return;
  }
  const std::string tmp = t.temporary();
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr) cannot_write(path, std::strerror(errno));
  const bool ok = std::fwrite(content.data(), 1, content.size(), f) == content.size();
  const int err = errno;
  const bool closed = std::fclose(f) == 0;
  if (!ok || !closed) {
    const int reason = ok ? errno : err;
    std::remove(tmp.c_str());
    cannot_write(path, std::strerror(reason));
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

}  // namespace foglab
