// foglab — sensor_msgs/Imu records in ROS 1 bags (rosbag.h).
//
// The ROS library's side (opening the bag, its topics, the messages' bytes) is the plugin
// foglab_rosbag.so (rosbag_ros.cc; rosbag_plugin.h says why a plugin), loaded here the first
// time a bag is read or written. This file reads the bag in a child process, puts the messages
// on a uniform time grid (see "The time grid" below), and writes bags through temporaries.
#include "foglab/io/rosbag.h"

#include <dlfcn.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <malloc.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/core/output.h"
#include "readers_internal.h"
#include "rosbag_plugin.h"
#include "stamp_grid.h"

namespace foglab::io {
namespace {

using internal::quoted_path;
using internal::throw_data_error;

using bag::MessageBlock;
using bag::MessageSink;
using bag::TopicRead;

// The plugin, loaded once: from beside the binary that holds this code (a Python package
// carries it beside its module), from the library folder of an installation beside it, from
// the build tree, then from the installation's folder. One of another build (its ABI digest
// differs) is passed over.
const bag::Plugin* load_plugin() {
  std::vector<std::filesystem::path> candidates;
  // The binary: a shared object (the Python module) by its loaded path, else the program.
  Dl_info info{};
  std::error_code error;
  const bool shared = ::dladdr(reinterpret_cast<void*>(&load_plugin), &info) != 0 &&
                      info.dli_fname != nullptr && info.dli_fname[0] == '/';
  const std::filesystem::path self = shared ? std::filesystem::path(info.dli_fname)
                                            : std::filesystem::canonical("/proc/self/exe", error);
  if (!self.empty()) {
    candidates.push_back(self.parent_path() / FOGLAB_ROSBAG_PLUGIN_NAME);
    candidates.push_back(self.parent_path() / ".." / FOGLAB_ROSBAG_PLUGIN_LIBDIR /
                         FOGLAB_ROSBAG_PLUGIN_NAME);
  }
  candidates.emplace_back(FOGLAB_ROSBAG_PLUGIN_BUILD_PATH);
  candidates.emplace_back(FOGLAB_ROSBAG_PLUGIN_INSTALL_PATH);
  std::vector<std::string> reasons;
  for (const std::filesystem::path& candidate : candidates) {
    if (!std::filesystem::is_regular_file(candidate, error)) continue;
    void* handle = ::dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      const char* why = ::dlerror();
      reasons.push_back(fmt::format("{}: {}", candidate.string(), why ? why : "dlopen failed"));
      continue;
    }
    using Entry = const bag::Plugin* (*)();
    const auto entry = reinterpret_cast<Entry>(::dlsym(handle, "foglab_rosbag_plugin"));
    const bag::Plugin* plugin = entry != nullptr ? entry() : nullptr;
    if (plugin != nullptr && std::strcmp(plugin->abi, kRosbagPluginAbi) == 0) return plugin;
    reasons.push_back(fmt::format(
        "{}: {}", candidate.string(),
        plugin == nullptr ? "not a foglab ROS bag plugin" : "built from another foglab version"));
    ::dlclose(handle);
  }
  throw std::runtime_error(fmt::format(
      "cannot read or write ROS bags: foglab's ROS bag plugin ({}) cannot be loaded ({}); it "
      "is built with foglab (target foglab_rosbag) and installed in {}",
      FOGLAB_ROSBAG_PLUGIN_NAME,
      reasons.empty() ? "not found" : fmt::to_string(fmt::join(reasons, "; ")),
      std::filesystem::path(FOGLAB_ROSBAG_PLUGIN_INSTALL_PATH).parent_path().string()));
}

const bag::Plugin& plugin() {
  static const bag::Plugin* const loaded = load_plugin();
  return *loaded;
}

// The record's six channels.
std::vector<double>& channel(ImuRecord& record, std::size_t j) {
  return j < 3 ? record.angular_velocity_rad_s[j] : record.linear_acceleration_m_s2[j - 3];
}

// The sink that fills the record: the stamps and the six channels, each channel with one
// sample's room more (the analysis integrates a record into its angle record, one point more,
// in place, and would otherwise reallocate it) and on transparent huge pages (core/numeric.h).
class RecordSink : public MessageSink {
 public:
  RecordSink(std::vector<std::int64_t>& stamps_ns, ImuRecord& record)
      : stamps_ns_(stamps_ns), record_(record) {}
  void start(std::size_t capacity) override {
    stamps_ns_.clear();
    stamps_ns_.reserve(capacity);
    for (std::size_t j = 0; j < 6; ++j) {
      std::vector<double>& values = channel(record_, j);
      values.clear();
      values.reserve(capacity + 1);
      advise_huge_pages(values.data(), capacity + 1);
    }
  }
  void messages(const MessageBlock& block) override {
    const auto n = static_cast<std::ptrdiff_t>(block.count);
    stamps_ns_.insert(stamps_ns_.end(), block.stamps_ns.begin(), block.stamps_ns.begin() + n);
    for (std::size_t j = 0; j < 6; ++j) {
      channel(record_, j)
          .insert(channel(record_, j).end(), block.values[j].begin(), block.values[j].begin() + n);
    }
  }
  void receive_times(const std::int64_t* stamps_ns, std::size_t count) override {
    count = std::min(count, stamps_ns_.size() - next_receive_time_);
    std::copy_n(stamps_ns, count,
                stamps_ns_.begin() + static_cast<std::ptrdiff_t>(next_receive_time_));
    next_receive_time_ += count;
  }

 private:
  std::vector<std::int64_t>& stamps_ns_;
  ImuRecord& record_;
  std::size_t next_receive_time_ = 0;
};

// --- Reading in a child process --------------------------------------------------------------
//
// rosbag trusts the offsets and lengths of its index and of the records in a chunk: a damaged
// one makes it read outside its buffers (a crash, not an exception; the index's offsets are
// never checked against the chunk). So the bag is read in a child process, and a crash there
// is a DataError here, as for HDF5 in mat_checks.cc. Without a process to spare, it is read
// here.
//
// The child does all of it, from opening the bag on: opening reads the whole index (a tree
// node a message, 0.7 GB for 10^7 messages), which is done once and never freed (the child
// ends without destructors: freeing the nodes one by one takes seconds). It sends the
// messages through a pipe, block by block, as it reads them, and this process puts them into
// the record meanwhile, on the other core: no memory holds the record twice, and the first
// touch of the record's memory, slow on virtual machines, overlaps the reading. What the child
// has to say at the end (an error, the frame) goes through a small shared page.
//
// On the pipe, each block is a BlockHeader and its payload: for kStart, the capacity (one
// uint64); for kMessages, `count` stamps then `count` values of each channel; for
// kReceiveTimes, `count` stamps.
enum class BlockKind : std::uint32_t { kStart = 1, kMessages = 2, kReceiveTimes = 3 };
struct BlockHeader {
  BlockKind kind;
  std::uint32_t count;
};

// Writes all of `bytes` to `fd`; throws when the reader has gone.
void write_all(int fd, const void* data, std::size_t bytes) {
  const auto* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t put = ::write(fd, p, bytes);
    if (put < 0 && errno == EINTR) continue;
    if (put <= 0) throw std::runtime_error("the pipe to the parent process closed");
    p += put;
    bytes -= static_cast<std::size_t>(put);
  }
}

// Reads all of `bytes` from `fd`; false at the end of the pipe (the child ended, or crashed).
bool read_all(int fd, void* data, std::size_t bytes) {
  auto* p = static_cast<char*>(data);
  while (bytes > 0) {
    const ssize_t got = ::read(fd, p, bytes);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return false;
    p += got;
    bytes -= static_cast<std::size_t>(got);
  }
  return true;
}

// The child's sink: each block into the pipe.
class PipeSink : public MessageSink {
 public:
  explicit PipeSink(int fd) : fd_(fd) {}
  void start(std::size_t capacity) override {
    const BlockHeader header{BlockKind::kStart, 0};
    const auto value = static_cast<std::uint64_t>(capacity);
    write_all(fd_, &header, sizeof(header));
    write_all(fd_, &value, sizeof(value));
  }
  void messages(const MessageBlock& block) override {
    const auto n = static_cast<std::size_t>(block.count);
    const BlockHeader header{BlockKind::kMessages, static_cast<std::uint32_t>(n)};
    write_all(fd_, &header, sizeof(header));
    write_all(fd_, block.stamps_ns.data(), n * sizeof(std::int64_t));
    for (const auto& values : block.values) write_all(fd_, values.data(), n * sizeof(double));
  }
  void receive_times(const std::int64_t* stamps_ns, std::size_t count) override {
    const BlockHeader header{BlockKind::kReceiveTimes, static_cast<std::uint32_t>(count)};
    write_all(fd_, &header, sizeof(header));
    write_all(fd_, stamps_ns, count * sizeof(std::int64_t));
  }

 private:
  int fd_;
};

// Takes the child's blocks from `fd` into `sink` until the pipe ends.
void receive_blocks(int fd, MessageSink& sink) {
  const auto block = std::make_unique<MessageBlock>();
  BlockHeader header{};
  while (read_all(fd, &header, sizeof(header))) {
    const std::size_t n = header.count;
    if (n > MessageBlock::kMessages) return;  // not from our child: its report decides
    if (header.kind == BlockKind::kStart) {
      std::uint64_t capacity = 0;
      if (!read_all(fd, &capacity, sizeof(capacity))) return;
      sink.start(static_cast<std::size_t>(capacity));
    } else if (header.kind == BlockKind::kMessages) {
      block->count = n;
      if (!read_all(fd, block->stamps_ns.data(), n * sizeof(std::int64_t))) return;
      for (auto& values : block->values) {
        if (!read_all(fd, values.data(), n * sizeof(double))) return;
      }
      sink.messages(*block);
    } else if (header.kind == BlockKind::kReceiveTimes) {
      if (!read_all(fd, block->stamps_ns.data(), n * sizeof(std::int64_t))) return;
      sink.receive_times(block->stamps_ns.data(), n);
    } else {
      return;
    }
  }
}

// What the child reports at the end, in anonymous memory shared with it.
struct ChildReport {
  int failed = 0;  // 1: `message` holds a DataError's, 2: a UsageError's
  int done = 0;    // 1: the child got to its end
  std::uint64_t count = 0;
  int header_stamps = 0;
  char topic[1024] = {};
  char frame_id[256] = {};
  char message[4096] = {};
};

class ReportMemory {
 public:
  ReportMemory() {
    data_ = ::mmap(nullptr, sizeof(ChildReport), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS,
                   -1, 0);
    if (data_ == MAP_FAILED) throw std::bad_alloc();
    new (data_) ChildReport();
  }
  ~ReportMemory() { ::munmap(data_, sizeof(ChildReport)); }
  ReportMemory(const ReportMemory&) = delete;
  ReportMemory& operator=(const ReportMemory&) = delete;
  ChildReport& report() const { return *static_cast<ChildReport*>(data_); }

 private:
  void* data_;
};

void copy_text(char* to, std::size_t size, const std::string& text) {
  const std::size_t n = std::min(size - 1, text.size());
  std::memcpy(to, text.data(), n);
  to[n] = '\0';
}

// The index's tree of a node a message is allocated node by node from the heap; on ordinary
// pages a third of opening a bag goes to page faults. So the reading process grows its heap in
// one step large enough for the index of an uncompressed bag of `file_bytes` (whose messages
// take at least 300 bytes each, their nodes 64) and advises transparent huge pages for it.
// Advice only: without it, ordinary pages.
void prepare_heap_for_index(std::uint64_t file_bytes) {
#if defined(M_TOP_PAD) && defined(M_MMAP_THRESHOLD) && defined(MADV_HUGEPAGE)
  constexpr std::uint64_t kHugePage = std::uint64_t{2} << 20;
  const std::uint64_t pad = std::min<std::uint64_t>(file_bytes / 4, INT_MAX);
  if (pad < 16 * kHugePage) return;
  ::mallopt(M_TOP_PAD, static_cast<int>(pad));
  // One allocation from the heap (not mapped apart), larger than what is left of it, makes
  // the heap grow by the pad.
  ::mallopt(M_MMAP_THRESHOLD, 4 << 20);
  const auto before = reinterpret_cast<std::uintptr_t>(::sbrk(0));
  void* volatile grow = std::malloc(std::size_t{1} << 20);
  std::free(grow);
  const auto after = reinterpret_cast<std::uintptr_t>(::sbrk(0));
  const std::uintptr_t first = (before + kHugePage - 1) & ~(kHugePage - 1);
  if (after > first + kHugePage) {
    (void)::madvise(reinterpret_cast<void*>(first), after - first, MADV_HUGEPAGE);
  }
#else
  (void)file_bytes;
#endif
}

// The child process: reads the bag into the pipe `fd`, and reports.
[[noreturn]] void child_reads(int fd, const std::string& path, const BagReadOptions& options,
                              ChildReport& report) {
  try {
    prepare_heap_for_index(internal::regular_file_size(path).value_or(0));
    PipeSink sink(fd);
    const TopicRead read = plugin().read_topic(path, options, sink, /*keep_index=*/true);
    report.count = read.count;
    report.header_stamps = read.header_stamps ? 1 : 0;
    copy_text(report.topic, sizeof(report.topic), read.topic);
    copy_text(report.frame_id, sizeof(report.frame_id), read.frame_id);
  } catch (const UsageError& e) {
    report.failed = 2;
    copy_text(report.message, sizeof(report.message), e.what());
  } catch (const std::exception& e) {
    report.failed = 1;
    copy_text(report.message, sizeof(report.message), e.what());
  }
  report.done = 1;
  ::_exit(0);
}

// A pipe's two ends, closed when destroyed.
class Pipe {
 public:
  Pipe() {
    if (::pipe2(fds_.data(), O_CLOEXEC) != 0) {
      fds_ = {-1, -1};
      return;
    }
#ifdef F_SETPIPE_SZ
    // Room for a few blocks (64 KiB by default: a block would take four turns of the two
    // processes); the system's limit for users is 1 MiB by default. Failure only costs speed.
    (void)::fcntl(fds_[1], F_SETPIPE_SZ, 1 << 20);
#endif
  }
  ~Pipe() {
    close_read();
    close_write();
  }
  Pipe(const Pipe&) = delete;
  Pipe& operator=(const Pipe&) = delete;
  bool usable() const { return fds_[0] >= 0; }
  int read_end() const { return fds_[0]; }
  int write_end() const { return fds_[1]; }
  void close_read() { close_end(0); }
  void close_write() { close_end(1); }

 private:
  void close_end(std::size_t k) {
    if (fds_[k] >= 0) ::close(fds_[k]);
    fds_[k] = -1;
  }
  std::array<int, 2> fds_{};
};

// Reads the bag into `stamps_ns` and the record's channels: in a child process (above), or
// here without one.
TopicRead read_guarded(const std::string& path, const BagReadOptions& options,
                       std::vector<std::int64_t>& stamps_ns, ImuRecord& record) {
  const bag::Plugin& ros = plugin();  // loaded before the fork, in this process
  RecordSink sink(stamps_ns, record);
  ReportMemory report_memory;
  Pipe pipe;
  std::fflush(nullptr);
  const pid_t pid = pipe.usable() ? ::fork() : -1;
  if (pid < 0) return ros.read_topic(path, options, sink, /*keep_index=*/false);
  if (pid == 0) {
    pipe.close_read();
    child_reads(pipe.write_end(), path, options, report_memory.report());
  }
  pipe.close_write();
  try {
    receive_blocks(pipe.read_end(), sink);
  } catch (...) {
    // This side failed (out of memory): the child is stopped, not left blocked on the pipe.
    ::kill(pid, SIGKILL);
    while (::waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
    }
    throw;
  }
  pipe.close_read();  // a child still writing (a damaged pipe protocol) gets EPIPE and ends
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  const ChildReport& report = report_memory.report();
  if (WIFSIGNALED(status)) {
    throw_data_error(path, fmt::format("damaged ROS 1 bag: the ROS library crashed reading it "
                                       "({}): an offset or length in its index or chunks is "
                                       "wrong",
                                       ::strsignal(WTERMSIG(status))));
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || report.done != 1) {
    throw_data_error(path, fmt::format("reading the bag failed (the reading process ended with "
                                       "status {})",
                                       status));
  }
  if (report.failed == 2) throw UsageError(report.message);
  if (report.failed != 0) throw DataError(report.message);
  if (stamps_ns.size() != report.count) {
    throw_data_error(path, fmt::format("reading the bag failed: {} messages read, {} received",
                                       report.count, stamps_ns.size()));
  }
  TopicRead read;
  read.topic = report.topic;
  read.count = static_cast<std::size_t>(report.count);
  read.frame_id = report.frame_id;
  read.header_stamps = report.header_stamps != 0;
  return read;
}

}  // namespace

bool has_bag_extension(const std::string& path) { return internal::has_extension(path, ".bag"); }

std::vector<BagTopic> list_bag_topics(const std::string& path) {
  return plugin().list_topics(path);
}

ImuRecord read_imu_bag(const std::string& path, const BagReadOptions& options) {
  if (options.sample_rate_hz &&
      !(std::isfinite(*options.sample_rate_hz) && *options.sample_rate_hz > 0.0)) {
    throw UsageError(
        fmt::format("BagReadOptions::sample_rate_hz must be a finite rate > 0 Hz "
                    "(got {})",
                    internal::format_value(*options.sample_rate_hz)));
  }
  // Read every message: its header stamp and the six values. Duplicates are dropped later,
  // in place, once the grid is known.
  ImuRecord record;
  record.path = path;
  std::vector<std::int64_t> stamps_ns;
  const TopicRead read = read_guarded(path, options, stamps_ns, record);
  record.topic = read.topic;
  record.frame_id = read.frame_id;
  record.timing.stamp_source = read.header_stamps ? "header.stamp" : "bag receive time";
  if (!read.header_stamps) {
    record.notes.emplace_back(Text::io_note_zero_stamps, read.topic);
  }
  const std::size_t n = stamps_ns.size();
  if (n < 2) {
    throw_data_error(path, fmt::format("topic '{}' has {} message{} that can be read; at least 2 "
                                       "are needed",
                                       read.topic, n, n == 1 ? "" : "s"));
  }
  record.timing.messages = n;
  record.timing.median_step_s = internal::median_step_s(stamps_ns);
  record.start_time_s = static_cast<double>(stamps_ns.front()) * 1e-9;
  if (options.sample_rate_hz) {
    record.sample_rate_hz = *options.sample_rate_hz;
    return record;
  }
  if (record.timing.median_step_s <= 0.0) {
    throw_data_error(path, fmt::format("the {} {}s of topic '{}' do not increase: all are {} s", n,
                                       record.timing.stamp_source, read.topic,
                                       internal::format_value(record.start_time_s)));
  }

  // The grid (stamp_grid.h), then the samples kept on it, compacted in place.
  internal::StampGrid grid = internal::fit_stamp_grid(stamps_ns, record.timing.median_step_s);
  if (grid.scatter_rms_steps > internal::kMostScatterSteps) {
    throw_data_error(
        path, fmt::format("topic '{}': the {}s scatter {:.2f} of a step about the uniform grid "
                          "that fits them best (evenly spread: 0.29; up to {} is read as "
                          "jitter), so the messages cannot be put on their sample slots; give "
                          "BagReadOptions::sample_rate_hz to read them as evenly spaced",
                          read.topic, record.timing.stamp_source, grid.scatter_rms_steps,
                          internal::kMostScatterSteps));
  }
  record.gaps = std::move(grid.gaps);
  record.timing.duplicates_dropped = grid.dropped.size();
  for (std::size_t j = 0; j < 3; ++j) {
    internal::drop_entries(record.angular_velocity_rad_s[j], grid.dropped);
    internal::drop_entries(record.linear_acceleration_m_s2[j], grid.dropped);
  }
  if (record.timing.duplicates_dropped > 0) {
    record.notes.emplace_back(Text::io_note_duplicates, record.timing.duplicates_dropped, n,
                              read.topic,
                              read.header_stamps ? Text::io_stamp_header : Text::io_stamp_receive);
  }
  if (n - grid.dropped.size() < 2) {
    throw_data_error(
        path, fmt::format("topic '{}': fewer than 2 messages on distinct time slots", read.topic));
  }
  record.timing.jitter_rms_s = grid.jitter_rms_s;
  record.timing.jitter_max_s = grid.jitter_max_s;
  if (!(grid.step_s > 0.0)) {
    throw_data_error(
        path, fmt::format("topic '{}': the stamps give no positive sample step", read.topic));
  }
  record.sample_rate_hz = 1.0 / grid.step_s;
  return record;
}

// --- writing ---------------------------------------------------------------------------------

namespace {

// ROS time: unsigned 32-bit seconds and nanoseconds.
constexpr double kMaxRosTime_s = 4294967295.0;

void check_content(const std::string& path, const ImuBagContent& content) {
  const std::size_t n = content.stamps_s.size();
  if (content.topic.empty()) cannot_write(path, "the topic name is empty");
  for (std::size_t j = 0; j < 3; ++j) {
    if (content.angular_velocity_rad_s[j].size() != n ||
        content.linear_acceleration_m_s2[j].size() != n) {
      cannot_write(path, fmt::format("{} stamps, but angular_velocity_rad_s[{}] has {} values "
                                     "and linear_acceleration_m_s2[{}] {}",
                                     n, j, content.angular_velocity_rad_s[j].size(), j,
                                     content.linear_acceleration_m_s2[j].size()));
    }
  }
  if (!content.receive_times_s.empty() && content.receive_times_s.size() != n) {
    cannot_write(path,
                 fmt::format("{} stamps, but {} receive times", n, content.receive_times_s.size()));
  }
  auto check_time = [&](double t, std::size_t i, std::string_view what, double least) {
    if (!(std::isfinite(t) && t >= least && t <= kMaxRosTime_s)) {
      cannot_write(path,
                   fmt::format("{} of message {} is {} s: ROS time holds {} to {} s", what, i + 1,
                               internal::format_value(t), internal::format_value(least),
                               internal::format_value(kMaxRosTime_s)));
    }
  };
  for (std::size_t i = 0; i < n; ++i) {
    check_time(content.stamps_s[i], i, "the stamp", 0.0);
    if (!content.receive_times_s.empty()) {
      // A bag stores no message received before ros::TIME_MIN (1 ns).
      check_time(content.receive_times_s[i], i, "the receive time", 1e-9);
    }
  }
}

}  // namespace

void write_imu_bag(const std::string& path, const ImuBagContent& content) {
  check_content(path, content);
  const bag::Plugin& ros = plugin();  // a missing plugin is not a failure to write
  const OutputTarget target = output_target(path);
  if (target.standard_output) {
    cannot_write(path,
                 "a ROS bag cannot go to standard output (it is written with seeks); give a "
                 "file name");
  }
  const std::string tmp = target.temporary();
  std::string reason;
  int error_number = 0;
  bool opened = false;
  try {
    errno = 0;
    ros.write_messages(tmp, content, opened);
  } catch (const std::exception& e) {
    error_number = errno;
    reason = e.what();
  }
  if (!reason.empty()) {
    discard_temporary(tmp);
    // The system's word decides, as in writer.cc: a full disk is a DataError, a file that
    // cannot be created (permissions) a UsageError.
    const bool storage = error_number == ENOSPC || error_number == EDQUOT ||
                         error_number == EFBIG || error_number == EIO;
    if (storage || (!opened && error_number != 0)) write_failed(path, error_number);
    throw DataError(fmt::format("cannot write '{}': {}", path, reason));
  }
  commit_temporary(target, tmp);
}

}  // namespace foglab::io
