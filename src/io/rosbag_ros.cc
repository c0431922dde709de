// foglab — the ROS library's side of reading and writing sensor_msgs/Imu bags: the plugin
// foglab_rosbag.so (rosbag_plugin.h says why a plugin), loaded by rosbag.cc.
//
// The library does the bag's format (records, chunks, bz2/lz4, the index); this file opens the
// bag, chooses the topic and copies the six channels out of the messages. Every library call
// that reads the file may throw (rosbag::BagException, ros::serialization's stream overruns,
// std::bad_alloc for a length read from a damaged record): each becomes a DataError naming the
// file.
#include <console_bridge/console.h>
#include <fmt/format.h>
#include <ros/serialization.h>
#include <rosbag/bag.h>
#include <rosbag/exceptions.h>
#include <rosbag/query.h>
#include <rosbag/view.h>
#include <sensor_msgs/Imu.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <exception>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/io/channels.h"
#include "readers_internal.h"
#include "rosbag_plugin.h"

namespace foglab::io::bag {
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

// A message's serialised bytes, as MessageInstance::write() hands them over (its Stream).
struct SerializedMessage {
  std::vector<std::uint8_t> bytes;
  std::uint8_t* advance(std::uint32_t size) {
    bytes.resize(size);
    return bytes.data();
  }
};

// Reads the messages of `topic`, whose index counts `capacity`, into `sink`; returns how many
// were read. Each is deserialised into one message object, reused (instantiate<> would
// allocate one a message). Throws DataError naming the message.
std::size_t read_messages(rosbag::Bag& bag, const std::string& path, const std::string& topic,
                          std::size_t capacity, MessageSink& sink, TopicRead& read) {
  std::size_t index = 0;  // 1-based in messages, once incremented
  try {
    rosbag::View view(bag, rosbag::TopicQuery(topic));
    // The check instantiate<> makes on each message, made once a connection: the connection's
    // MD5 sum is not sensor_msgs/Imu's for a message definition of another version.
    const std::string md5sum = ros::message_traits::md5sum<ImuMessage>();
    for (const rosbag::ConnectionInfo* c : view.getConnections()) {
      if (c->md5sum != md5sum) {
        throw_data_error(path, fmt::format("topic '{}': type {} with MD5 sum {} is not the {} "
                                           "foglab reads (MD5 sum {})",
                                           topic, c->datatype, c->md5sum, kImuMessageType, md5sum));
      }
    }
    SerializedMessage serialized;
    ImuMessage imu;
    const auto block = std::make_unique<MessageBlock>();
    for (const rosbag::MessageInstance& m : view) {
      if (index == capacity) {
        throw_data_error(path, fmt::format("topic '{}' has more messages than its index counts "
                                           "({}): a damaged bag",
                                           topic, capacity));
      }
      ++index;
      m.write(serialized);
      ros::serialization::IStream stream(serialized.bytes.data(),
                                         static_cast<std::uint32_t>(serialized.bytes.size()));
      ros::serialization::deserialize(stream, imu);
      if (index == 1) read.frame_id = imu.header.frame_id;
      const std::array<double, 6> v = {imu.angular_velocity.x,    imu.angular_velocity.y,
                                       imu.angular_velocity.z,    imu.linear_acceleration.x,
                                       imu.linear_acceleration.y, imu.linear_acceleration.z};
      const std::size_t slot = block->count++;
      for (std::size_t j = 0; j < v.size(); ++j) {
        if (!std::isfinite(v[j])) {
          static constexpr std::array<const char*, 6> kFields = {
              "angular_velocity.x",    "angular_velocity.y",    "angular_velocity.z",
              "linear_acceleration.x", "linear_acceleration.y", "linear_acceleration.z"};
          throw_data_error(path, fmt::format("topic '{}', message {}: {} is {}", topic, index,
                                             kFields[j], v[j]));
        }
        block->values[j][slot] = v[j];
      }
      block->stamps_ns[slot] = nanoseconds(imu.header.stamp);
      read.header_stamps = read.header_stamps || block->stamps_ns[slot] != 0;
      if (block->count == MessageBlock::kMessages) {
        sink.messages(*block);
        block->count = 0;
      }
    }
    if (block->count > 0) sink.messages(*block);
    if (!read.header_stamps) {
      // The receive times are in the index: no message is read again.
      std::size_t k = 0;
      block->count = 0;
      for (const rosbag::MessageInstance& m : view) {
        if (k++ == index) break;
        block->stamps_ns[block->count++] = nanoseconds(m.getTime());
        if (block->count == MessageBlock::kMessages) {
          sink.receive_times(block->stamps_ns.data(), block->count);
          block->count = 0;
        }
      }
      if (block->count > 0) sink.receive_times(block->stamps_ns.data(), block->count);
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

// Everything read_imu_bag() asks of the ROS library: the bag opened, the topic chosen and
// checked against `options`, then its messages read into `sink`.
TopicRead read_topic(rosbag::Bag& bag, const std::string& path, const BagReadOptions& options,
                     MessageSink& sink) {
  open_bag(bag, path);
  const std::vector<BagTopic> topics = topics_of(bag, path);
  const BagTopic& topic = choose_topic(topics, path, options.topic);
  if (options.max_samples && topic.messages > *options.max_samples) {
    throw_data_error(path, fmt::format("topic '{}' has {} messages, more than {}: the limit for "
                                       "one record (BagReadOptions::max_samples)",
                                       topic.name, topic.messages, *options.max_samples));
  }
  if (topic.messages < 2) {
    throw_data_error(path, fmt::format("topic '{}' has {} message{}; at least 2 are needed",
                                       topic.name, topic.messages, topic.messages == 1 ? "" : "s"));
  }
  TopicRead read;
  read.topic = topic.name;
  const auto capacity = static_cast<std::size_t>(topic.messages);
  sink.start(capacity);
  read.count = read_messages(bag, path, topic.name, capacity, sink, read);
  return read;
}

ros::Time ros_time(double seconds) {
  const auto ns = static_cast<std::int64_t>(std::llround(seconds * 1e9));
  return ros::Time(static_cast<std::uint32_t>(ns / 1'000'000'000),
                   static_cast<std::uint32_t>(ns % 1'000'000'000));
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

std::vector<BagTopic> list_topics(const std::string& path) {
  rosbag::Bag bag;
  open_bag(bag, path);
  return topics_of(bag, path);
}

TopicRead read_topic_of(const std::string& path, const BagReadOptions& options, MessageSink& sink,
                        bool keep_index) {
  if (!keep_index) {
    rosbag::Bag bag;
    return read_topic(bag, path, options, sink);
  }
  auto* bag = new rosbag::Bag();  // never freed (Plugin::read_topic)
  return read_topic(*bag, path, options, sink);
}

void write_messages(const std::string& file, const ImuBagContent& content, bool& opened) {
  silence_library_log();
  BagWriter writer(file);
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
}

constexpr Plugin kPlugin = {kRosbagPluginAbi, list_topics, read_topic_of, write_messages};

}  // namespace
}  // namespace foglab::io::bag

extern "C" __attribute__((visibility("default"))) const foglab::io::bag::Plugin*
foglab_rosbag_plugin() {
  return &foglab::io::bag::kPlugin;
}
