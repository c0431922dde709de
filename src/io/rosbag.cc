// foglab — sensor_msgs/Imu records in ROS 1 bags, through rosbag_storage (rosbag.h).
//
// The library does the bag's format (records, chunks, bz2/lz4, the index); this file chooses
// the topic, copies the six channels out of the messages, and puts the messages on a uniform
// time grid (see "The time grid" below). Every library call that reads the file may throw
// (rosbag::BagException, ros::serialization's stream overruns, std::bad_alloc for a length
// read from a damaged record): each becomes a DataError naming the file.
#include "foglab/io/rosbag.h"

#include <console_bridge/console.h>
#include <fmt/format.h>
#include <ros/serialization.h>
#include <rosbag/bag.h>
#include <rosbag/exceptions.h>
#include <rosbag/query.h>
#include <rosbag/view.h>
#include <sensor_msgs/Imu.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <map>
#include <memory>
#include <new>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/core/output.h"
#include "foglab/io/channels.h"
#include "readers_internal.h"

namespace foglab::io {
namespace {

using internal::quoted_path;
using internal::throw_data_error;

// Every ROS 1 bag starts with this line (version 2.0; the library also reads 1.2).
constexpr std::string_view kBagMagic = "#ROSBAG V";

// rosbag logs through console_bridge, which prints to stderr; its messages are the library's
// own business (an error reaches us as an exception), so they are silenced once.
void silence_library_log() {
  static const bool silenced = [] {
    console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
    return true;
  }();
  (void)silenced;
}

// Opens `path` for reading. A bag is read with seeks (its index is at the end), so standard
// input, a FIFO or a device cannot be one.
void open_bag(rosbag::Bag& bag, const std::string& path) {
  silence_library_log();
  if (path == "-") {
    throw UsageError(
        "a ROS bag cannot be read from standard input (it is read with seeks); "
        "give the file's name");
  }
  const std::optional<std::uint64_t> size = internal::regular_file_size(path);
  if (!size) {
    throw UsageError(fmt::format("{}: a ROS bag must be a regular file (it is read with seeks)",
                                 quoted_path(path)));
  }
  if (*size == 0) throw_data_error(path, "the file is empty (not a ROS 1 bag)");
  // The library's own message for a file of another kind is "Error reading version line".
  std::string head(kBagMagic.size(), '\0');
  {
    std::ifstream in(path, std::ios::binary);
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  }
  if (head != kBagMagic) {
    throw_data_error(path,
                     fmt::format("not a ROS 1 bag (it does not start with '{}2.0')", kBagMagic));
  }
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagUnindexedException&) {
    throw_data_error(path,
                     "the bag has no index: the recording was cut short or is still being "
                     "written (the recorder writes the index when it closes the bag; "
                     "'rosbag reindex' can rebuild it)");
  } catch (const std::exception& e) {
    // The index lies at the end of the file, behind the chunks: a bag cut short loses it, and
    // the library then reads whatever lies where the file header says the index begins.
    throw_data_error(path, fmt::format("truncated or damaged ROS 1 bag: cannot read its index "
                                       "({}); 'rosbag reindex' may recover the messages",
                                       e.what()));
  }
}

// The topics of an open bag: type and message count, by name.
std::vector<BagTopic> topics_of(rosbag::Bag& bag, const std::string& path) {
  std::map<std::string, BagTopic> by_name;
  try {
    rosbag::View view(bag);
    for (const rosbag::ConnectionInfo* c : view.getConnections()) {
      BagTopic& t = by_name[c->topic];
      t.name = c->topic;
      if (t.type.empty()) t.type = c->datatype;
    }
    for (auto& [name, topic] : by_name) {
      rosbag::View one(bag, rosbag::TopicQuery(name));
      topic.messages = one.size();
    }
  } catch (const std::exception& e) {
    throw_data_error(path, fmt::format("damaged ROS 1 bag: cannot list its topics ({})", e.what()));
  }
  std::vector<BagTopic> topics;
  for (auto& [name, topic] : by_name) topics.push_back(std::move(topic));
  return topics;
}

// "NAME (TYPE)", short enough for list_names() to keep whole in most bags.
std::string describe(const BagTopic& t) { return fmt::format("{} ({})", t.name, t.type); }

// The topic to read: the one asked for, or the only sensor_msgs/Imu topic.
const BagTopic& choose_topic(const std::vector<BagTopic>& topics, const std::string& path,
                             const std::string& wanted) {
  std::vector<std::string> imu_names;
  std::vector<std::string> all;
  for (const BagTopic& t : topics) {
    if (t.type == kImuMessageType) imu_names.push_back(t.name);
    all.push_back(describe(t));
  }
  if (!wanted.empty()) {
    for (const BagTopic& t : topics) {
      if (t.name != wanted) continue;
      if (t.type != kImuMessageType) {
        throw UsageError(fmt::format("{}: topic '{}' holds {} messages, not {}{}",
                                     quoted_path(path), wanted, t.type, kImuMessageType,
                                     imu_names.empty()
                                         ? std::string(" (the bag has none)")
                                         : fmt::format(" (the bag's {} topics: {})",
                                                       kImuMessageType, list_names(imu_names))));
      }
      return t;
    }
    throw UsageError(fmt::format(
        "{}: no topic '{}'; {}", quoted_path(path), wanted,
        imu_names.empty()
            ? fmt::format("the bag has no {} topic (its topics: {})", kImuMessageType,
                          all.empty() ? std::string("none") : list_names(all))
            : fmt::format("its {} topics: {}", kImuMessageType, list_names(imu_names))));
  }
  if (imu_names.empty()) {
    throw_data_error(path, fmt::format("no {} topic; the bag holds {}", kImuMessageType,
                                       all.empty() ? std::string("no messages") : list_names(all)));
  }
  if (imu_names.size() > 1) {
    throw UsageError(fmt::format("{}: {} {} topics ({}): choose one (BagReadOptions::topic)",
                                 quoted_path(path), imu_names.size(), kImuMessageType,
                                 list_names(imu_names)));
  }
  for (const BagTopic& t : topics) {
    if (t.name == imu_names.front()) return t;
  }
  throw_data_error(path, "internal: topic vanished");  // not reached
}

// The ROS 1 message classes are templates on an allocator, and the generated code names a
// string's as ContainerAllocator::rebind<char>::other, which std::allocator<void> lost in C++20
// (sensor_msgs::Imu is Imu_<std::allocator<void>>). With an allocator that still has rebind the
// same classes compile, and their layout, serialisation and MD5 sum are sensor_msgs::Imu's.
struct RosAllocator : std::allocator<void> {
  template <typename T>
  struct rebind {
    using other = std::allocator<T>;
  };
};
using ImuMessage = sensor_msgs::Imu_<RosAllocator>;

std::int64_t nanoseconds(const ros::Time& t) {
  return static_cast<std::int64_t>(t.sec) * 1'000'000'000 + static_cast<std::int64_t>(t.nsec);
}

// What reading a topic's messages gives besides the channels.
struct MessagesRead {
  std::string frame_id;
  bool header_stamps = false;  // any header stamp non-zero
};

// Reads the `capacity` messages of `topic` (the index's count) into `stamps_ns` and the six
// arrays `values[0..5]` (angular velocity x, y, z, then linear acceleration), each of room for
// `capacity`; returns how many were read. Throws DataError naming the message.
std::size_t read_messages(const std::string& path, const std::string& topic, std::size_t capacity,
                          std::int64_t* stamps_ns, const std::array<double*, 6>& values,
                          MessagesRead& read) {
  rosbag::Bag bag;
  open_bag(bag, path);
  std::size_t index = 0;  // 1-based in messages, once incremented
  try {
    rosbag::View view(bag, rosbag::TopicQuery(topic));
    for (const rosbag::MessageInstance& m : view) {
      if (index == capacity) {
        throw_data_error(path, fmt::format("topic '{}' has more messages than its index counts "
                                           "({}): a damaged bag",
                                           topic, capacity));
      }
      ++index;
      // instantiate<> deserialises into a new message; it returns null when the connection's
      // type or MD5 sum is not sensor_msgs/Imu's (a message definition of another version).
      const boost::shared_ptr<const ImuMessage> imu = m.instantiate<ImuMessage>();
      if (!imu) {
        throw_data_error(path,
                         fmt::format("topic '{}', message {}: type {} with MD5 sum {} is "
                                     "not the {} foglab reads (MD5 sum {})",
                                     topic, index, m.getDataType(), m.getMD5Sum(), kImuMessageType,
                                     ros::message_traits::md5sum<ImuMessage>()));
      }
      if (index == 1) read.frame_id = imu->header.frame_id;
      const std::array<double, 6> v = {imu->angular_velocity.x,    imu->angular_velocity.y,
                                       imu->angular_velocity.z,    imu->linear_acceleration.x,
                                       imu->linear_acceleration.y, imu->linear_acceleration.z};
      for (std::size_t j = 0; j < v.size(); ++j) {
        if (!std::isfinite(v[j])) {
          static constexpr std::array<const char*, 6> kFields = {
              "angular_velocity.x",    "angular_velocity.y",    "angular_velocity.z",
              "linear_acceleration.x", "linear_acceleration.y", "linear_acceleration.z"};
          throw_data_error(path, fmt::format("topic '{}', message {}: {} is {}", topic, index,
                                             kFields[j], v[j]));
        }
        values[j][index - 1] = v[j];
      }
      stamps_ns[index - 1] = nanoseconds(imu->header.stamp);
      read.header_stamps = read.header_stamps || stamps_ns[index - 1] != 0;
    }
    if (!read.header_stamps) {
      // The receive times are in the index: no message is read again.
      std::size_t k = 0;
      for (const rosbag::MessageInstance& m : view) {
        if (k < index) stamps_ns[k++] = nanoseconds(m.getTime());
      }
    }
  } catch (const DataError&) {
    throw;
  } catch (const std::exception& e) {
    throw_data_error(path, fmt::format("truncated or damaged ROS 1 bag: topic '{}', message {}: "
                                       "{}",
                                       topic, index, e.what()));
  }
  return index;
}

// Anonymous memory shared with a child process; unmapped when destroyed.
class SharedMemory {
 public:
  explicit SharedMemory(std::size_t bytes) : bytes_(std::max<std::size_t>(bytes, 1)) {
    // MAP_POPULATE: the pages are faulted in at once, much faster than one by one as the
    // child writes them (on virtual machines a first touch can limit writes to 200 MB/s).
    data_ = ::mmap(nullptr, bytes_, PROT_READ | PROT_WRITE,
                   MAP_SHARED | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
    if (data_ == MAP_FAILED) throw std::bad_alloc();
  }
  ~SharedMemory() { ::munmap(data_, bytes_); }
  SharedMemory(const SharedMemory&) = delete;
  SharedMemory& operator=(const SharedMemory&) = delete;
  template <typename T>
  T* as() const {
    return static_cast<T*>(data_);
  }

 private:
  std::size_t bytes_;
  void* data_;
};

// What the child reports.
struct ChildReport {
  int failed = 0;  // 1: `message` holds the DataError's
  std::uint64_t count = 0;
  int header_stamps = 0;
  char frame_id[256] = {};
  char message[4096] = {};
};

void copy_text(char* to, std::size_t size, const std::string& text) {
  const std::size_t n = std::min(size - 1, text.size());
  std::memcpy(to, text.data(), n);
  to[n] = '\0';
}

// rosbag trusts the offsets and lengths of its index and of the records in a chunk: a
// damaged one makes it read outside its buffers (a crash, not an exception; the index's
// offsets are never checked against the chunk). So the messages are read in a child process
// into memory shared with this one, and a crash there is a DataError here, as for HDF5 in
// mat_checks.cc. Without a process to spare, they are read here. The child opens the bag
// itself: a bag opened here before the fork would be freed here after it, touching every page
// of its index (about 100 bytes a message) that the fork had marked copy-on-write.
void read_messages_guarded(const std::string& path, const std::string& topic, std::size_t capacity,
                           std::vector<std::int64_t>& stamps_ns, ImuRecord& record) {
  auto channel = [&record](std::size_t j) -> std::vector<double>& {
    return j < 3 ? record.angular_velocity_rad_s[j] : record.linear_acceleration_m_s2[j - 3];
  };
  SharedMemory report_memory(sizeof(ChildReport));
  std::vector<std::unique_ptr<SharedMemory>> arrays;
  for (std::size_t j = 0; j < 7; ++j) {
    arrays.push_back(std::make_unique<SharedMemory>(capacity * sizeof(double)));
  }
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) {
    arrays.clear();
    stamps_ns.resize(capacity);
    std::array<double*, 6> values{};
    for (std::size_t j = 0; j < 6; ++j) {
      channel(j).resize(capacity);
      values[j] = channel(j).data();
    }
    MessagesRead read;
    const std::size_t n = read_messages(path, topic, capacity, stamps_ns.data(), values, read);
    stamps_ns.resize(n);
    for (std::size_t j = 0; j < 6; ++j) channel(j).resize(n);
    record.frame_id = read.frame_id;
    record.timing.stamp_source = read.header_stamps ? "header.stamp" : "bag receive time";
    return;
  }
  if (pid == 0) {
    auto* report = new (report_memory.as<void>()) ChildReport();
    try {
      std::array<double*, 6> values{};
      for (std::size_t j = 0; j < 6; ++j) values[j] = arrays[j + 1]->as<double>();
      MessagesRead read;
      report->count =
          read_messages(path, topic, capacity, arrays[0]->as<std::int64_t>(), values, read);
      report->header_stamps = read.header_stamps ? 1 : 0;
      copy_text(report->frame_id, sizeof(report->frame_id), read.frame_id);
    } catch (const std::exception& e) {
      report->failed = 1;
      copy_text(report->message, sizeof(report->message), e.what());
    }
    ::_exit(0);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  const ChildReport& report = *report_memory.as<ChildReport>();
  if (WIFSIGNALED(status)) {
    throw_data_error(path, fmt::format("damaged ROS 1 bag: the ROS library crashed reading topic "
                                       "'{}' ({}): an offset or length in its index or chunks "
                                       "is wrong",
                                       topic, ::strsignal(WTERMSIG(status))));
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw_data_error(path, fmt::format("reading topic '{}' failed (the reading process ended "
                                       "with status {})",
                                       topic, status));
  }
  if (report.failed != 0) throw DataError(report.message);
  // Copied out array by array, each released once copied, so that the peak is about one set.
  // Each channel on transparent huge pages (core/numeric.h), for the same reason.
  const auto n = static_cast<std::size_t>(report.count);
  stamps_ns.assign(arrays[0]->as<std::int64_t>(), arrays[0]->as<std::int64_t>() + n);
  arrays[0].reset();
  for (std::size_t j = 0; j < 6; ++j) {
    // One sample's room more: the analysis integrates a record into its angle record (one
    // point more) in place, and would otherwise reallocate it.
    channel(j).reserve(n + 1);
    advise_huge_pages(channel(j).data(), n + 1);
    channel(j).assign(arrays[j + 1]->as<double>(), arrays[j + 1]->as<double>() + n);
    arrays[j + 1].reset();
  }
  record.frame_id = report.frame_id;
  record.timing.stamp_source = report.header_stamps != 0 ? "header.stamp" : "bag receive time";
}

// --- The time grid (rosbag.h explains what it is for) ---------------------------------------
//
// A uniform grid has two parameters: its step T and its phase. A stamp's position relative to
// the grid, frac((t - t0) / T), is its phase; jitter spreads the phases about the grid's, and a
// dropped or repeated message shifts a stamp by whole steps, which leaves its phase alone. So
// the step and the phase are found from phases (circular statistics: the angle of the mean of
// exp(2 pi i phase)), never by counting steps, and a stamp then lies in the slot
// round((t - t0) / T - phase). Rounding against the grid rather than against the previous
// stamp is what keeps jitter of up to +-40 % of a step from making a gap (a step between two
// jittered stamps can be 0.2 or 1.8 steps, which step counting would call a duplicate or a
// gap).
//   1. T starts as the median step. It is refined in stages: the phase differences of stamps
//      L messages apart show L times the step's relative error (mod 1), so each stage takes a
//      lag four times longer than the last, up to half the record, while L times the
//      remaining error stays well below half a step.
//   2. The phase is the circular mean over a window of about 4000 messages around each
//      message (blocks of 256, unwrapped from block to block), which follows a slow drift of
//      the recording host's clock against the sensor's.
//   3. A message whose slot is not after the previous message's is dropped; slots skipped are
//      a gap. The rate is then the least-squares slope of stamp against slot.

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Angle, in cycles in (-0.5, 0.5], of a sum of unit vectors.
double cycles(double sum_cos, double sum_sin) { return std::atan2(sum_sin, sum_cos) / kTwoPi; }

// `x` minus the nearest integer: in [-0.5, 0.5].
double wrap(double x) { return x - std::round(x); }

double median_step_s(const std::vector<std::int64_t>& stamps_ns) {
  std::vector<std::int64_t> steps;
  steps.reserve(stamps_ns.size() - 1);
  for (std::size_t k = 1; k < stamps_ns.size(); ++k) {
    if (stamps_ns[k] > stamps_ns[k - 1]) steps.push_back(stamps_ns[k] - stamps_ns[k - 1]);
  }
  if (steps.empty()) return 0.0;
  const auto middle = steps.begin() + static_cast<std::ptrdiff_t>((steps.size() - 1) / 2);
  std::nth_element(steps.begin(), middle, steps.end());
  return static_cast<double>(*middle) * 1e-9;
}

// Step 1 above: the step [s] refined from `step_s` by phase differences at growing lags.
double refine_step_s(const std::vector<std::int64_t>& stamps_ns, double step_s) {
  constexpr std::size_t kMaxPairs = std::size_t{1} << 17;  // spread over the record
  const std::size_t n = stamps_ns.size();
  for (std::size_t lag = 1; lag <= (n - 1) / 2 || lag == 1; lag *= 4) {
    const std::size_t pairs = n - lag;
    const std::size_t stride = std::max<std::size_t>(1, pairs / kMaxPairs);
    double c = 0.0;
    double s = 0.0;
    std::size_t used = 0;
    for (std::size_t k = 0; k < pairs; k += stride) {
      const double steps = static_cast<double>(stamps_ns[k + lag] - stamps_ns[k]) * 1e-9 / step_s;
      // Only pairs `lag` slots apart: across a gap (a pause of an hour) the phase difference
      // is the step's error times the slots between, not times the lag.
      if (std::round(steps) != static_cast<double>(lag)) continue;
      c += std::cos(kTwoPi * steps);
      s += std::sin(kTwoPi * steps);
      ++used;
    }
    if (used == 0) break;
    // The pairs' phase differences are the lag times step_s' relative error.
    step_s *= 1.0 + cycles(c, s) / static_cast<double>(lag);
    if (lag > (n - 1) / 2) break;
  }
  return step_s;
}

// Step 2 above: each message's slot (the first message's is 0).
std::vector<std::int64_t> grid_slots(const std::vector<std::int64_t>& stamps_ns, double step_s) {
  constexpr std::size_t kBlock = 256;
  constexpr std::size_t kHalfWindowBlocks = 8;
  const std::size_t n = stamps_ns.size();
  const std::int64_t t0 = stamps_ns.front();
  auto position = [&](std::size_t k) {  // in steps from the first stamp
    return static_cast<double>(stamps_ns[k] - t0) * 1e-9 / step_s;
  };
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<double> block_cos(blocks, 0.0);
  std::vector<double> block_sin(blocks, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const double angle = kTwoPi * position(k);
    block_cos[k / kBlock] += std::cos(angle);
    block_sin[k / kBlock] += std::sin(angle);
  }
  // The windowed phase at each block, unwrapped from block to block.
  std::vector<double> phase(blocks);
  double c = 0.0;
  double s = 0.0;
  for (std::size_t b = 0; b < std::min(blocks, kHalfWindowBlocks + 1); ++b) {
    c += block_cos[b];
    s += block_sin[b];
  }
  for (std::size_t b = 0; b < blocks; ++b) {
    if (b > 0) {
      if (b + kHalfWindowBlocks < blocks) {
        c += block_cos[b + kHalfWindowBlocks];
        s += block_sin[b + kHalfWindowBlocks];
      }
      if (b > kHalfWindowBlocks) {
        c -= block_cos[b - kHalfWindowBlocks - 1];
        s -= block_sin[b - kHalfWindowBlocks - 1];
      }
    }
    const double angle = cycles(c, s);
    phase[b] = b == 0 ? angle : phase[b - 1] + wrap(angle - phase[b - 1]);
  }
  // The phase between block centres by linear interpolation.
  std::vector<std::int64_t> slots(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double at = (static_cast<double>(k) + 0.5) / kBlock - 0.5;
    double p = phase.front();
    if (at >= static_cast<double>(blocks - 1)) {
      p = phase.back();
    } else if (at > 0.0) {
      const auto b = static_cast<std::size_t>(at);
      const double f = at - static_cast<double>(b);
      p = phase[b] + f * (phase[b + 1] - phase[b]);
    }
    slots[k] = std::llround(position(k) - p);
  }
  const std::int64_t first = slots.front();
  for (std::int64_t& slot : slots) slot -= first;
  return slots;
}

}  // namespace

bool has_bag_extension(const std::string& path) {
  constexpr std::string_view kExtension = ".bag";
  return path.size() > kExtension.size() &&
         std::equal(kExtension.rbegin(), kExtension.rend(), path.rbegin(), [](char e, char p) {
           return std::tolower(static_cast<unsigned char>(p)) == e;
         });
}

std::vector<BagTopic> list_bag_topics(const std::string& path) {
  rosbag::Bag bag;
  open_bag(bag, path);
  return topics_of(bag, path);
}

ImuRecord read_imu_bag(const std::string& path, const BagReadOptions& options) {
  if (options.sample_rate_hz &&
      !(std::isfinite(*options.sample_rate_hz) && *options.sample_rate_hz > 0.0)) {
    throw UsageError(
        fmt::format("BagReadOptions::sample_rate_hz must be a finite rate > 0 Hz "
                    "(got {})",
                    internal::format_value(*options.sample_rate_hz)));
  }
  std::vector<BagTopic> topics;
  {
    rosbag::Bag bag;
    open_bag(bag, path);
    topics = topics_of(bag, path);
  }
  const BagTopic& topic = choose_topic(topics, path, options.topic);

  ImuRecord record;
  record.path = path;
  record.topic = topic.name;
  if (options.max_samples && topic.messages > *options.max_samples) {
    throw_data_error(path, fmt::format("topic '{}' has {} messages, more than {}: the limit for "
                                       "one record (BagReadOptions::max_samples)",
                                       topic.name, topic.messages, *options.max_samples));
  }
  if (topic.messages < 2) {
    throw_data_error(path, fmt::format("topic '{}' has {} message{}; at least 2 are needed",
                                       topic.name, topic.messages, topic.messages == 1 ? "" : "s"));
  }

  // Read every message: its header stamp and the six values. Duplicates are dropped later,
  // in place, once the grid is known.
  const auto count = static_cast<std::size_t>(topic.messages);
  std::vector<std::int64_t> stamps_ns;
  read_messages_guarded(path, topic.name, count, stamps_ns, record);
  if (record.timing.stamp_source != "header.stamp") {
    record.notes.push_back(fmt::format(
        "every header.stamp of topic '{}' is zero: the times are the bag's receive times, "
        "which carry the recording host's delays",
        topic.name));
  }
  const std::size_t n = stamps_ns.size();
  if (n < 2) {
    throw_data_error(path, fmt::format("topic '{}' has {} message{} that can be read; at least 2 "
                                       "are needed",
                                       topic.name, n, n == 1 ? "" : "s"));
  }
  record.timing.messages = n;
  record.timing.median_step_s = median_step_s(stamps_ns);
  record.start_time_s = static_cast<double>(stamps_ns.front()) * 1e-9;
  if (options.sample_rate_hz) {
    record.sample_rate_hz = *options.sample_rate_hz;
    return record;
  }
  if (record.timing.median_step_s <= 0.0) {
    throw_data_error(path, fmt::format("the {} {}s of topic '{}' do not increase: all are {} s", n,
                                       record.timing.stamp_source, topic.name,
                                       internal::format_value(record.start_time_s)));
  }

  // The grid, then the samples kept on it (in place) and their gaps.
  const double step_s = refine_step_s(stamps_ns, record.timing.median_step_s);
  const std::vector<std::int64_t> slots = grid_slots(stamps_ns, step_s);
  std::size_t kept = 1;
  std::int64_t last_slot = slots.front();
  for (std::size_t k = 1; k < n; ++k) {
    const std::int64_t skipped = slots[k] - last_slot - 1;
    if (skipped < 0 || stamps_ns[k] <= stamps_ns[kept - 1]) {
      ++record.timing.duplicates_dropped;
      continue;
    }
    if (skipped > 0) record.gaps.push_back(Gap{static_cast<std::int64_t>(kept), skipped});
    last_slot = slots[k];
    stamps_ns[kept] = stamps_ns[k];
    for (std::size_t j = 0; j < 3; ++j) {
      record.angular_velocity_rad_s[j][kept] = record.angular_velocity_rad_s[j][k];
      record.linear_acceleration_m_s2[j][kept] = record.linear_acceleration_m_s2[j][k];
    }
    ++kept;
  }
  stamps_ns.resize(kept);
  for (std::size_t j = 0; j < 3; ++j) {
    record.angular_velocity_rad_s[j].resize(kept);
    record.linear_acceleration_m_s2[j].resize(kept);
  }
  if (record.timing.duplicates_dropped > 0) {
    record.notes.push_back(fmt::format(
        "{} of the {} messages of topic '{}' dropped: each fell on the time slot of the message "
        "before it, or earlier (a repeated or out-of-order {})",
        record.timing.duplicates_dropped, n, topic.name, record.timing.stamp_source));
  }
  if (kept < 2) {
    throw_data_error(
        path, fmt::format("topic '{}': fewer than 2 messages on distinct time slots", topic.name));
  }

  // Least squares of stamp (from the first, [s]) against slot, in two passes for accuracy;
  // the slot of sample i is i plus the samples missing before it.
  auto for_each_sample = [&](auto&& f) {
    std::int64_t missing = 0;
    std::size_t g = 0;
    for (std::size_t i = 0; i < kept; ++i) {
      while (g < record.gaps.size() &&
             record.gaps[g].before_sample == static_cast<std::int64_t>(i)) {
        missing += record.gaps[g++].missing_samples;
      }
      f(static_cast<double>(static_cast<std::int64_t>(i) + missing),
        static_cast<double>(stamps_ns[i] - stamps_ns.front()) * 1e-9);
    }
  };
  double mean_slot = 0.0;
  double mean_s = 0.0;
  for_each_sample([&](double slot, double t_s) {
    mean_slot += slot;
    mean_s += t_s;
  });
  mean_slot /= static_cast<double>(kept);
  mean_s /= static_cast<double>(kept);
  double sxx = 0.0;
  double sxy = 0.0;
  for_each_sample([&](double slot, double t_s) {
    sxx += (slot - mean_slot) * (slot - mean_slot);
    sxy += (slot - mean_slot) * (t_s - mean_s);
  });
  const double fitted_step_s = sxy / sxx;
  double sum_squares = 0.0;
  double largest = 0.0;
  for_each_sample([&](double slot, double t_s) {
    const double residual = t_s - mean_s - fitted_step_s * (slot - mean_slot);
    sum_squares += residual * residual;
    largest = std::max(largest, std::abs(residual));
  });
  record.timing.jitter_rms_s = std::sqrt(sum_squares / static_cast<double>(kept));
  record.timing.jitter_max_s = largest;
  if (!(fitted_step_s > 0.0)) {
    throw_data_error(
        path, fmt::format("topic '{}': the stamps give no positive sample step", topic.name));
  }
  record.sample_rate_hz = 1.0 / fitted_step_s;
  return record;
}

// --- writing ---------------------------------------------------------------------------------

namespace {

// ROS time: unsigned 32-bit seconds and nanoseconds.
constexpr double kMaxRosTime_s = 4294967295.0;

ros::Time ros_time(double seconds) {
  const auto ns = static_cast<std::int64_t>(std::llround(seconds * 1e9));
  return ros::Time(static_cast<std::uint32_t>(ns / 1'000'000'000),
                   static_cast<std::uint32_t>(ns % 1'000'000'000));
}

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

// The library's writer, with what it needs on a failure: it reports a failed fwrite() as a
// BagIOException, and its destructor then closes the bag, which writes the index and may
// throw again, from a destructor (std::terminate). So on a failure the bag is closed once
// more under try; if that throws too, the bag object is abandoned (its file handle with it)
// rather than destroyed.
class BagWriter {
 public:
  explicit BagWriter(const std::string& file) : bag_(std::make_unique<rosbag::Bag>()) {
    bag_->open(file, rosbag::bagmode::Write);
  }
  ~BagWriter() {
    if (!bag_) return;
    try {
      bag_->close();
    } catch (...) {
      (void)bag_.release();
    }
  }
  BagWriter(const BagWriter&) = delete;
  BagWriter& operator=(const BagWriter&) = delete;
  rosbag::Bag& bag() { return *bag_; }

 private:
  std::unique_ptr<rosbag::Bag> bag_;
};

}  // namespace

void write_imu_bag(const std::string& path, const ImuBagContent& content) {
  check_content(path, content);
  silence_library_log();
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
    BagWriter writer(tmp);
    opened = true;
    ImuMessage imu;
    imu.header.frame_id = content.frame_id;
    // ROS: a covariance of all zeros means "unknown"; -1 in its first element means "not
    // provided", as for the orientation, which an IMU record does not have.
    imu.orientation_covariance[0] = -1.0;
    for (std::size_t i = 0; i < content.stamps_s.size(); ++i) {
      imu.header.seq = static_cast<std::uint32_t>(i);
      imu.header.stamp = ros_time(content.stamps_s[i]);
      imu.angular_velocity.x = content.angular_velocity_rad_s[0][i];
      imu.angular_velocity.y = content.angular_velocity_rad_s[1][i];
      imu.angular_velocity.z = content.angular_velocity_rad_s[2][i];
      imu.linear_acceleration.x = content.linear_acceleration_m_s2[0][i];
      imu.linear_acceleration.y = content.linear_acceleration_m_s2[1][i];
      imu.linear_acceleration.z = content.linear_acceleration_m_s2[2][i];
      const ros::Time received = content.receive_times_s.empty()
                                     ? std::max(imu.header.stamp, ros::TIME_MIN)
                                     : ros_time(content.receive_times_s[i]);
      writer.bag().write(content.topic, received, imu);
    }
    writer.bag().close();
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
