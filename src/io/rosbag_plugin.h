// The part of ROS 1 bag reading and writing that needs the ROS library (rosbag_storage,
// roscpp_serialization, sensor_msgs), built as a plugin, foglab_rosbag.so, that foglab_io loads
// with dlopen() the first time a bag is read or written (rosbag.cc).
//
// Why a plugin: rosbag_storage brings some forty shared libraries with it (Python 3, Boost,
// pluginlib, class_loader, ...), and the dynamic loader binding them cost every foglab command
// about 15 ms at start, bags or not (issue 19: `foglab allan` on 2e7 samples takes 0.18 s).
//
// Both sides include this header and are built together; the plugin's table carries
// kRosbagPluginAbi, foglab's version and a digest of the headers whose types cross between
// them (this one, foglab/io/rosbag.h, core/error.h, core/gaps.h: src/CMakeLists.txt), and a
// table of any other digest is refused.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "foglab/io/rosbag.h"
#include "rosbag_plugin_abi.h"  // kRosbagPluginAbi, written by CMake

namespace foglab::io::bag {

// A block of messages as the plugin hands them on, in the layout they are stored in: the
// stamps, then each of the six channels (angular velocity x, y, z, then linear acceleration),
// the first `count` of each in use.
struct MessageBlock {
  static constexpr std::size_t kMessages = 4096;
  std::uint64_t count = 0;
  std::array<std::int64_t, kMessages> stamps_ns{};
  std::array<std::array<double, kMessages>, 6> values{};
};

// Where read_topic() hands on what it reads.
class MessageSink {
 public:
  virtual ~MessageSink() = default;
  // The topic has `capacity` messages by its index; called once, before any block.
  virtual void start(std::size_t capacity) = 0;
  // The next block of messages, stamped with their header stamps.
  virtual void messages(const MessageBlock& block) = 0;
  // Only when every header stamp was zero: the next `count` receive times, from the first
  // message on, to stamp the messages with instead.
  virtual void receive_times(const std::int64_t* stamps_ns, std::size_t count) = 0;
};

// What reading a topic gives besides the messages.
struct TopicRead {
  std::string topic;
  std::size_t count = 0;  // messages read
  std::string frame_id;
  bool header_stamps = false;  // any header stamp non-zero
};

// The plugin's functions. Each reports a bad file as DataError and a bad request as
// UsageError (foglab/core/error.h), naming the file.
struct Plugin {
  const char* abi;  // kRosbagPluginAbi of the plugin's build
  // The bag's topics: type and message count, by name.
  std::vector<BagTopic> (*list_topics)(const std::string& path);
  // Opens the bag, chooses and checks the topic (options.topic, max_samples) and reads its
  // messages into `sink`. With `keep_index`, the bag's index (a tree node a message) is never
  // freed: a process about to end saves the seconds that freeing it node by node takes.
  TopicRead (*read_topic)(const std::string& path, const BagReadOptions& options, MessageSink& sink,
                          bool keep_index);
  // Writes `content` (checked already) as a new bag at `file`; throws std::exception on any
  // failure, with errno as the system left it. `opened`: whether the file was created.
  void (*write_messages)(const std::string& file, const ImuBagContent& content, bool& opened);
};

}  // namespace foglab::io::bag

// The plugin's one exported symbol.
extern "C" const foglab::io::bag::Plugin* foglab_rosbag_plugin();
