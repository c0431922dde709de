// Tests of reading and writing ROS 1 bags of sensor_msgs/Imu messages: round trips, the time
// grid (jitter, dropped and repeated messages), damaged files, the topic errors, and bags
// written by the ROS Python library (tests/io/make_imu_bag.py) from a CSV of truth.
#include "foglab/io/rosbag.h"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "reader_fixture.h"
#include "support/expect.h"
#include "support/files.h"

namespace foglab::io {
namespace {

namespace fs = std::filesystem;
using test::message_of;
using ::testing::ElementsAre;
using ::testing::ElementsAreArray;
using ::testing::FieldsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::StartsWith;

constexpr double kStart_s = 1.7e9;  // a stamp of 2023, as a recording has

// `n` messages every 1/rate_hz from kStart_s, with values of a seeded generator.
ImuBagContent uniform_content(std::size_t n, double rate_hz, unsigned seed = 1) {
  ImuBagContent c;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gyro(0.0, 1e-3);
  std::normal_distribution<double> accel(0.0, 0.02);
  for (std::size_t k = 0; k < n; ++k) {
    c.stamps_s.push_back(kStart_s + static_cast<double>(k) / rate_hz);
    for (std::size_t j = 0; j < 3; ++j) {
      c.angular_velocity_rad_s[j].push_back(gyro(rng));
      c.linear_acceleration_m_s2[j].push_back(accel(rng) + (j == 2 ? 9.81 : 0.0));
    }
  }
  return c;
}

// Removes message `k` (0-based) from every field.
void erase_message(ImuBagContent& c, std::size_t k) {
  auto at = [k](auto& v) { return v.begin() + static_cast<std::ptrdiff_t>(k); };
  c.stamps_s.erase(at(c.stamps_s));
  if (!c.receive_times_s.empty()) c.receive_times_s.erase(at(c.receive_times_s));
  for (std::size_t j = 0; j < 3; ++j) {
    c.angular_velocity_rad_s[j].erase(at(c.angular_velocity_rad_s[j]));
    c.linear_acceleration_m_s2[j].erase(at(c.linear_acceleration_m_s2[j]));
  }
}

// Adds uniform jitter of +-fraction of a step to every stamp but the first.
void add_jitter(ImuBagContent& c, double rate_hz, double fraction, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-fraction / rate_hz, fraction / rate_hz);
  for (std::size_t k = 1; k < c.stamps_s.size(); ++k) c.stamps_s[k] += u(rng);
}

void expect_values(const ImuRecord& r, const ImuBagContent& c) {
  for (std::size_t j = 0; j < 3; ++j) {
    EXPECT_THAT(r.angular_velocity_rad_s[j], ElementsAreArray(c.angular_velocity_rad_s[j]));
    EXPECT_THAT(r.linear_acceleration_m_s2[j], ElementsAreArray(c.linear_acceleration_m_s2[j]));
  }
}

class RosbagTest : public ReaderTest {
 protected:
  std::string bag(const std::string& name, const ImuBagContent& content) {
    const std::string path = dir_.file(name);
    write_imu_bag(path, content);
    return path;
  }
  static BagReadOptions topic(const std::string& name) {
    BagReadOptions o;
    o.topic = name;
    return o;
  }
};

TEST_F(RosbagTest, RoundTripIsExact) {
  const ImuBagContent c = uniform_content(2000, 400.0);
  const std::string path = bag("rec.bag", c);
  const ImuRecord r = read_imu_bag(path);
  EXPECT_EQ(r.path, path);
  EXPECT_EQ(r.topic, "/imu");
  EXPECT_EQ(r.frame_id, "imu");
  EXPECT_NEAR(r.sample_rate_hz, 400.0, 400.0 * 1e-9);
  EXPECT_NEAR(r.start_time_s, kStart_s, 1e-6);
  EXPECT_THAT(r.gaps, IsEmpty());
  EXPECT_THAT(r.notes, IsEmpty());
  EXPECT_EQ(r.timing.messages, 2000u);
  EXPECT_EQ(r.timing.duplicates_dropped, 0u);
  EXPECT_EQ(r.timing.stamp_source, "header.stamp");
  // A double holds a time of 1.7e9 s to 0.24 us, and ROS time to the nanosecond.
  EXPECT_NEAR(r.timing.median_step_s, 0.0025, 3e-7);
  EXPECT_LT(r.timing.jitter_max_s, 3e-7);
  expect_values(r, c);

  const std::vector<BagTopic> topics = list_bag_topics(path);
  ASSERT_EQ(topics.size(), 1u);
  EXPECT_EQ(topics[0].name, "/imu");
  EXPECT_EQ(topics[0].type, "sensor_msgs/Imu");
  EXPECT_EQ(topics[0].messages, 2000u);
}

TEST_F(RosbagTest, WriterReplacesAFileAndLeavesNoTemporary) {
  const std::string path = write("rec.bag", "old content");
  write_imu_bag(path, uniform_content(10, 100.0));
  EXPECT_EQ(read_imu_bag(path).timing.messages, 10u);
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir_.path())) {
    names.push_back(entry.path().filename().string());
  }
  EXPECT_THAT(names, ElementsAre("rec.bag"));
}

// Jitter measured against the grid, not against the neighbouring stamp: a step between two
// jittered stamps runs from 0.4 to 1.6 steps (0.2 to 1.8 at 40 %), and none is a gap or a
// duplicate.
TEST_F(RosbagTest, ThirtyPercentJitterMakesNoGapAndShowsInTheJitter) {
  const double rate_hz = 400.0;
  ImuBagContent c = uniform_content(100000, rate_hz);
  add_jitter(c, rate_hz, 0.3, 7);
  const ImuRecord r = read_imu_bag(bag("jitter.bag", c));
  EXPECT_THAT(r.gaps, IsEmpty());
  EXPECT_EQ(r.timing.duplicates_dropped, 0u);
  EXPECT_NEAR(r.sample_rate_hz, rate_hz, rate_hz * 1e-6);
  // Uniform on +-0.3 steps: rms 0.3 / sqrt(3) steps.
  const double step_s = 1.0 / rate_hz;
  EXPECT_NEAR(r.timing.jitter_rms_s, 0.3 * step_s / std::sqrt(3.0), 0.01 * 0.3 * step_s);
  EXPECT_GT(r.timing.jitter_max_s, 0.29 * step_s);
  EXPECT_LT(r.timing.jitter_max_s, 0.31 * step_s);
  expect_values(r, c);
}

TEST_F(RosbagTest, FortyPercentJitterMakesNoGap) {
  const double rate_hz = 200.0;
  ImuBagContent c = uniform_content(200000, rate_hz);
  add_jitter(c, rate_hz, 0.4, 11);
  const ImuRecord r = read_imu_bag(bag("jitter40.bag", c));
  EXPECT_THAT(r.gaps, IsEmpty());
  EXPECT_EQ(r.timing.duplicates_dropped, 0u);
  EXPECT_NEAR(r.sample_rate_hz, rate_hz, rate_hz * 1e-6);
}

TEST_F(RosbagTest, DroppedMessagesAreGaps) {
  const double rate_hz = 400.0;
  ImuBagContent c = uniform_content(10000, rate_hz);
  add_jitter(c, rate_hz, 0.1, 3);
  erase_message(c, 5000);
  for (int k = 0; k < 5; ++k) erase_message(c, 100);  // messages 100 to 104
  const ImuRecord r = read_imu_bag(bag("drops.bag", c));
  EXPECT_THAT(r.gaps, ElementsAre(FieldsAre(100, 5), FieldsAre(4995, 1)));
  EXPECT_EQ(r.timing.messages, 9994u);
  EXPECT_EQ(r.timing.duplicates_dropped, 0u);
  EXPECT_NEAR(r.sample_rate_hz, rate_hz, rate_hz * 1e-6);
  expect_values(r, c);
}

TEST_F(RosbagTest, ALongPauseIsOneGap) {
  ImuBagContent c = uniform_content(3000, 100.0);
  // A logger's pause of 10 minutes after message 1000 (60000 samples).
  for (std::size_t k = 1000; k < c.stamps_s.size(); ++k) c.stamps_s[k] += 600.0;
  const ImuRecord r = read_imu_bag(bag("pause.bag", c));
  EXPECT_THAT(r.gaps, ElementsAre(FieldsAre(1000, 60000)));
  EXPECT_NEAR(r.sample_rate_hz, 100.0, 1e-6);
}

TEST_F(RosbagTest, StampsOnNoGridAreRefusedAndTheRateOptionReadsThem) {
  // event times (a Poisson process at 100 Hz): no sampling grid to put them on
  ImuBagContent c = uniform_content(4000, 100.0);
  std::mt19937_64 rng(12);
  std::exponential_distribution<double> step_s(100.0);
  double t_s = kStart_s;
  for (double& stamp : c.stamps_s) stamp = t_s += step_s(rng);
  const std::string path = bag("events.bag", c);
  const std::string message = test::message_of<DataError>([&] { read_imu_bag(path); });
  EXPECT_THAT(message, HasSubstr("the header.stamps scatter 0.2"));
  EXPECT_THAT(message, HasSubstr("BagReadOptions::sample_rate_hz"));
  BagReadOptions options;
  options.sample_rate_hz = 100.0;
  EXPECT_EQ(read_imu_bag(path, options).angular_velocity_rad_s[0].size(), 4000u);
}

TEST_F(RosbagTest, RepeatedAndOutOfOrderStampsAreDropped) {
  ImuBagContent c = uniform_content(1000, 100.0);
  ImuBagContent expected = c;
  c.stamps_s[300] = c.stamps_s[299];          // a repeated stamp
  c.stamps_s[600] = c.stamps_s[598] - 0.05;   // out of order, five steps back
  c.stamps_s[700] = c.stamps_s[699] + 0.001;  // a tenth of a step after its neighbour
  erase_message(expected, 700);
  erase_message(expected, 600);
  erase_message(expected, 300);
  const ImuRecord r = read_imu_bag(bag("dups.bag", c));
  EXPECT_EQ(r.timing.duplicates_dropped, 3u);
  EXPECT_EQ(r.timing.messages, 1000u);
  // Each dropped message leaves its slot empty.
  EXPECT_THAT(r.gaps, ElementsAre(FieldsAre(300, 1), FieldsAre(599, 1), FieldsAre(698, 1)));
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_THAT(r.notes[0].text(), HasSubstr("3 of the 1000 messages of topic '/imu' dropped"));
  expect_values(r, expected);
}

TEST_F(RosbagTest, ZeroHeaderStampsFallBackToReceiveTimes) {
  // 10,000 messages: the reading process sends them in blocks of 4096, the receive times too,
  // so a block sent out of place would show as gaps.
  ImuBagContent c = uniform_content(10000, 50.0);
  c.receive_times_s = c.stamps_s;
  add_jitter(c, 50.0, 0.05, 5);
  for (std::size_t k = 0; k < c.stamps_s.size(); ++k)
    std::swap(c.stamps_s[k], c.receive_times_s[k]);
  std::fill(c.stamps_s.begin(), c.stamps_s.end(), 0.0);
  const ImuRecord r = read_imu_bag(bag("zero.bag", c));
  EXPECT_EQ(r.timing.stamp_source, "bag receive time");
  EXPECT_NEAR(r.sample_rate_hz, 50.0, 50.0 * 1e-4);
  EXPECT_NEAR(r.start_time_s, kStart_s, 1e-6);
  EXPECT_THAT(r.gaps, IsEmpty());
  EXPECT_EQ(r.timing.messages, 10000u);
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_THAT(r.notes[0].text(), HasSubstr("receive times"));
  expect_values(r, c);
}

TEST_F(RosbagTest, SampleRateOptionIgnoresTheStamps) {
  ImuBagContent c = uniform_content(100, 10.0);
  erase_message(c, 50);
  BagReadOptions o;
  o.sample_rate_hz = 10.0;
  const ImuRecord r = read_imu_bag(bag("fs.bag", c), o);
  EXPECT_EQ(r.sample_rate_hz, 10.0);
  EXPECT_THAT(r.gaps, IsEmpty());
  EXPECT_EQ(r.angular_velocity_rad_s[0].size(), 99u);
  o.sample_rate_hz = -1.0;
  EXPECT_THAT(message_of<UsageError>([&] { read_imu_bag(dir_.file("fs.bag"), o); }),
              HasSubstr("sample_rate_hz"));
}

TEST_F(RosbagTest, MaxSamplesIsADataErrorNamingTheLimit) {
  const std::string path = bag("big.bag", uniform_content(101, 10.0));
  BagReadOptions o;
  o.max_samples = 100;
  const std::string m = message_of<DataError>([&] { read_imu_bag(path, o); });
  EXPECT_THAT(m, StartsWith("'" + path + "'"));
  EXPECT_THAT(m, HasSubstr("more than 100"));
  o.max_samples = 101;
  EXPECT_EQ(read_imu_bag(path, o).timing.messages, 101u);
}

TEST_F(RosbagTest, NonFiniteValueNamesTopicMessageAndField) {
  ImuBagContent c = uniform_content(20, 10.0);
  c.linear_acceleration_m_s2[1][6] = std::nan("");
  const std::string path = bag("nan.bag", c);
  const std::string m = message_of<DataError>([&] { read_imu_bag(path); });
  EXPECT_THAT(m, StartsWith("'" + path + "'"));
  EXPECT_THAT(m, HasSubstr("topic '/imu', message 7: linear_acceleration.y is nan"));
}

TEST_F(RosbagTest, OneMessageIsTooFew) {
  const std::string path = bag("one.bag", uniform_content(1, 10.0));
  EXPECT_THAT(message_of<DataError>([&] { read_imu_bag(path); }),
              HasSubstr("topic '/imu' has 1 message; at least 2 are needed"));
}

TEST_F(RosbagTest, AllStampsEqualIsADataError) {
  ImuBagContent c = uniform_content(10, 10.0);
  std::fill(c.stamps_s.begin(), c.stamps_s.end(), 5.0);
  const std::string path = bag("same.bag", c);
  EXPECT_THAT(message_of<DataError>([&] { read_imu_bag(path); }), HasSubstr("do not increase"));
}

TEST_F(RosbagTest, UnknownTopicIsAUsageErrorListingTheImuTopics) {
  const std::string path = bag("rec.bag", uniform_content(10, 10.0));
  const std::string m = message_of<UsageError>([&] { read_imu_bag(path, topic("/imu2")); });
  EXPECT_THAT(m, StartsWith("'" + path + "'"));
  EXPECT_THAT(m, HasSubstr("no topic '/imu2'; its sensor_msgs/Imu topics: /imu"));
}

TEST_F(RosbagTest, FilesThatAreNotBagsAreDataErrors) {
  const std::string empty = write("empty.bag", "");
  EXPECT_THAT(message_of<DataError>([&] { read_imu_bag(empty); }),
              AllOf(StartsWith("'" + empty + "'"), HasSubstr("empty")));
  const std::string text = write("text.bag", "t,rate\n0,1\n");
  EXPECT_THAT(message_of<DataError>([&] { read_imu_bag(text); }),
              AllOf(StartsWith("'" + text + "'"), HasSubstr("not a ROS 1 bag")));
  std::mt19937 rng(1);
  std::string noise(100000, '\0');
  for (char& ch : noise) ch = static_cast<char>(rng());
  const std::string random = write("random.bag", noise);
  EXPECT_THAT(message_of<DataError>([&] { list_bag_topics(random); }),
              HasSubstr("not a ROS 1 bag"));
  // Random bytes behind a bag's first line reach the library.
  const std::string behind = write("behind.bag", "#ROSBAG V2.0\n" + noise);
  EXPECT_THAT(message_of<DataError>([&] { read_imu_bag(behind); }), StartsWith("'" + behind + "'"));
  EXPECT_THROW(read_imu_bag("-"), UsageError);
  EXPECT_THROW(read_imu_bag(dir_.file("missing.bag")), UsageError);
}

// A bag cut short anywhere, in a chunk or in the index behind the chunks, is a DataError,
// never a crash.
TEST_F(RosbagTest, TruncatedBagIsADataErrorWhereverItIsCut) {
  const std::string whole = test::read_file(bag("whole.bag", uniform_content(8000, 400.0)));
  ASSERT_GT(whole.size(), 2u * 768 * 1024);  // several chunks of 768 KiB
  std::vector<std::size_t> cuts = {14,
                                   100,
                                   4096,
                                   768 * 1024 / 2,
                                   768 * 1024 + 333,
                                   whole.size() * 6 / 10,
                                   whole.size() - 100,
                                   whole.size() - 1};
  for (const std::size_t cut : cuts) {
    const std::string path = write(fmt::format("cut{}.bag", cut), whole.substr(0, cut));
    const std::string m = message_of<DataError>([&] { read_imu_bag(path); });
    EXPECT_THAT(m, StartsWith("'" + path + "'")) << "cut at " << cut;
  }
}

// Bytes changed anywhere (the file header, message data, record headers in a chunk, the
// index behind the chunks) give a DataError or other values, never a crash or an exception
// of another kind. rosbag itself crashes on some (an index offset outside its chunk).
TEST_F(RosbagTest, DamagedBagsNeverCrash) {
  const std::string whole = test::read_file(bag("whole.bag", uniform_content(4000, 400.0)));
  std::mt19937 rng(3);
  for (int trial = 0; trial < 150; ++trial) {
    std::string damaged = whole;
    // A third each in the first 4 KiB, anywhere, and the last 60 KB (the index).
    const std::size_t at = trial % 3 == 0   ? 13 + rng() % 4096
                           : trial % 3 == 1 ? 13 + rng() % (whole.size() - 17)
                                            : whole.size() - 4 - rng() % 60000;
    for (int k = 0; k < 4; ++k) damaged[at + k] = static_cast<char>(rng());
    const std::string path = write("damaged.bag", damaged);
    try {
      (void)read_imu_bag(path);
    } catch (const DataError& e) {
      EXPECT_THAT(e.what(), StartsWith("'" + path + "'"));
    } catch (const UsageError& e) {
      // A damaged connection record can rename the topic.
      EXPECT_THAT(e.what(), StartsWith("'" + path + "'"));
    }
  }
}

TEST_F(RosbagTest, WriterRefusesUnusableContent) {
  ImuBagContent c = uniform_content(10, 10.0);
  c.angular_velocity_rad_s[2].pop_back();
  EXPECT_THAT(message_of<UsageError>([&] { write_imu_bag(dir_.file("a.bag"), c); }),
              HasSubstr("angular_velocity_rad_s[2] has 9 values"));
  c = uniform_content(10, 10.0);
  c.stamps_s[3] = -1.0;
  EXPECT_THAT(message_of<UsageError>([&] { write_imu_bag(dir_.file("a.bag"), c); }),
              HasSubstr("the stamp of message 4 is -1 s"));
  c = uniform_content(10, 10.0);
  EXPECT_THROW(write_imu_bag(dir_.file("no/such/folder/a.bag"), c), UsageError);
  EXPECT_THROW(write_imu_bag("-", c), UsageError);
  EXPECT_FALSE(fs::exists(dir_.file("a.bag")));
}

// --- bags written by the ROS Python library (make_imu_bag.py) --------------------------------

class PythonBagTest : public RosbagTest {
 protected:
  void SetUp() override {
    if (std::system(fmt::format("'{}' -c 'import rosbag, sensor_msgs.msg, std_msgs.msg' "
                                ">/dev/null 2>&1",
                                FOGLAB_ROSBAG_PYTHON)
                        .c_str()) != 0) {
      GTEST_SKIP() << FOGLAB_ROSBAG_PYTHON
                   << " cannot import rosbag, sensor_msgs and std_msgs: install python3-rosbag, "
                      "python3-sensor-msgs and python3-std-msgs (scripts/install-deps.sh "
                      "--tests)";
    }
  }
  // The truth as CSV (shortest round-trip digits), and the bag made from it.
  std::string python_bag(const std::string& name, const ImuBagContent& c,
                         const std::string& arguments = "") {
    std::string csv = "stamp_s,gx,gy,gz,ax,ay,az\n";
    for (std::size_t k = 0; k < c.stamps_s.size(); ++k) {
      csv += fmt::format("{},{},{},{},{},{},{}\n", c.stamps_s[k], c.angular_velocity_rad_s[0][k],
                         c.angular_velocity_rad_s[1][k], c.angular_velocity_rad_s[2][k],
                         c.linear_acceleration_m_s2[0][k], c.linear_acceleration_m_s2[1][k],
                         c.linear_acceleration_m_s2[2][k]);
    }
    const std::string truth = write(name + ".csv", csv);
    const std::string path = dir_.file(name);
    const std::string command =
        fmt::format("'{}' '{}/tests/io/make_imu_bag.py' '{}' --csv '{}' {}", FOGLAB_ROSBAG_PYTHON,
                    FOGLAB_SOURCE_DIR, path, truth, arguments);
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return path;
  }
};

TEST_F(PythonBagTest, ReadsTheTruthWithJitterAndDrops) {
  const double rate_hz = 400.0;
  ImuBagContent c = uniform_content(6000, rate_hz, 21);
  add_jitter(c, rate_hz, 0.2, 22);
  erase_message(c, 4000);
  for (int k = 0; k < 3; ++k) erase_message(c, 250);
  for (const std::string compression : {"none", "bz2", "lz4"}) {
    SCOPED_TRACE(compression);
    const std::string path =
        python_bag(compression + ".bag", c, "--frame-id imu_link --compression " + compression);
    const ImuRecord r = read_imu_bag(path);
    EXPECT_EQ(r.frame_id, "imu_link");
    EXPECT_THAT(r.gaps, ElementsAre(FieldsAre(250, 3), FieldsAre(3997, 1)));
    EXPECT_NEAR(r.sample_rate_hz, rate_hz, rate_hz * 1e-5);
    EXPECT_NEAR(r.start_time_s, c.stamps_s[0], 1e-6);
    expect_values(r, c);
  }
}

TEST_F(PythonBagTest, TopicsOfOtherTypesAndSeveralImuTopics) {
  const ImuBagContent c = uniform_content(300, 100.0);
  const std::string two = python_bag("two.bag", c, "--second-imu-topic /imu2 --string-topic /log");
  const std::vector<BagTopic> topics = list_bag_topics(two);
  ASSERT_EQ(topics.size(), 3u);
  EXPECT_EQ(topics[0].name, "/imu");
  EXPECT_EQ(topics[1].name, "/imu2");
  EXPECT_EQ(topics[2].name, "/log");
  EXPECT_EQ(topics[2].type, "std_msgs/String");
  EXPECT_EQ(topics[2].messages, 3u);

  std::string m = message_of<UsageError>([&] { read_imu_bag(two); });
  EXPECT_THAT(m, StartsWith("'" + two + "'"));
  EXPECT_THAT(m, HasSubstr("2 sensor_msgs/Imu topics (/imu, /imu2): choose one"));
  m = message_of<UsageError>([&] { read_imu_bag(two, topic("/log")); });
  EXPECT_THAT(m, HasSubstr("topic '/log' holds std_msgs/String messages, not sensor_msgs/Imu"));
  m = message_of<UsageError>([&] { read_imu_bag(two, topic("/nope")); });
  EXPECT_THAT(m, HasSubstr("its sensor_msgs/Imu topics: /imu, /imu2"));
  const ImuRecord r = read_imu_bag(two, topic("/imu2"));
  EXPECT_EQ(r.topic, "/imu2");
  expect_values(r, c);
}

TEST_F(PythonBagTest, NoImuTopicIsADataErrorListingTheTopics) {
  const std::string strings = dir_.file("strings.bag");
  const std::string command = fmt::format(
      "'{}' -c \"import rosbag; from std_msgs.msg import String; "
      "b = rosbag.Bag('{}', 'w'); b.write('/chatter', String(data='hi')); b.close()\"",
      FOGLAB_ROSBAG_PYTHON, strings);
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::string m = message_of<DataError>([&] { read_imu_bag(strings); });
  EXPECT_THAT(m, StartsWith("'" + strings + "'"));
  EXPECT_THAT(m, HasSubstr("no sensor_msgs/Imu topic; the bag holds /chatter (std_msgs/String"));
}

TEST_F(PythonBagTest, ZeroHeaderStampsUseTheReceiveTimes) {
  const ImuBagContent c = uniform_content(400, 200.0);
  const ImuRecord r = read_imu_bag(python_bag("zero.bag", c, "--zero-stamps"));
  EXPECT_EQ(r.timing.stamp_source, "bag receive time");
  EXPECT_NEAR(r.sample_rate_hz, 200.0, 1e-6);
  EXPECT_THAT(r.gaps, IsEmpty());
  expect_values(r, c);
}

TEST_F(PythonBagTest, GeneratedTruthRoundTrips) {
  const std::string path = dir_.file("gen.bag");
  const std::string truth = dir_.file("gen.csv");
  const std::string command = fmt::format(
      "'{}' '{}/tests/io/make_imu_bag.py' '{}' --generate 1000 --seed 5 "
      "--rate-hz 125 --truth '{}' --compression bz2",
      FOGLAB_ROSBAG_PYTHON, FOGLAB_SOURCE_DIR, path, truth);
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const ImuRecord r = read_imu_bag(path);
  EXPECT_NEAR(r.sample_rate_hz, 125.0, 1e-6);
  std::ifstream in(truth);
  std::string line;
  std::getline(in, line);  // header
  std::size_t k = 0;
  while (std::getline(in, line)) {
    double v[7];
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3],
                          &v[4], &v[5], &v[6]),
              7);
    ASSERT_LT(k, r.angular_velocity_rad_s[0].size());
    for (std::size_t j = 0; j < 3; ++j) {
      EXPECT_EQ(r.angular_velocity_rad_s[j][k], v[1 + j]) << "message " << k + 1;
      EXPECT_EQ(r.linear_acceleration_m_s2[j][k], v[4 + j]) << "message " << k + 1;
    }
    ++k;
  }
  EXPECT_EQ(k, 1000u);
}

}  // namespace
}  // namespace foglab::io
