#!/usr/bin/env python3
"""Writes a ROS 1 bag of sensor_msgs/Imu messages with the ROS Python library (python3-rosbag),
so that foglab's reader is tested against bags it did not write itself (tests/io/rosbag_test.cc).

The messages come from a CSV of truth, one message a line:

    stamp_s,gx,gy,gz,ax,ay,az     (rad/s, m/s^2; a header line is allowed)

or are generated (--generate N) with random.gauss from --seed, at --rate-hz, and the truth is
written to --truth. Needs only python3, python3-rosbag, python3-sensor-msgs and, for
--string-topic, python3-std-msgs (Debian); no numpy.

Exit status: 0 when the bag is written, 2 for bad arguments, 3 when the ROS Python packages are
missing (the test then skips).
"""
import argparse
import csv
import random
import sys

try:
    import rosbag
    import rospy
    from sensor_msgs.msg import Imu
    from std_msgs.msg import String
except ImportError as e:  # the test skips on this status
    print(f"make_imu_bag.py: {e} (install python3-rosbag python3-sensor-msgs "
          "python3-std-msgs)", file=sys.stderr)
    sys.exit(3)


def ros_time(seconds):
    """rospy.Time of a stamp in seconds, to the nearest nanosecond (as foglab writes them)."""
    ns = round(seconds * 1e9)
    return rospy.Time(ns // 1_000_000_000, ns % 1_000_000_000)


def read_truth(path):
    rows = []
    with open(path, newline="") as f:
        for line_number, row in enumerate(csv.reader(f), start=1):
            if not row or row[0].startswith("#"):
                continue
            try:
                values = [float(x) for x in row]
            except ValueError:
                if line_number == 1:
                    continue  # a header line
                raise
            if len(values) != 7:
                sys.exit(f"make_imu_bag.py: {path}:{line_number}: expected 7 fields "
                         f"(stamp_s,gx,gy,gz,ax,ay,az), got {len(values)}")
            rows.append(values)
    return rows


def generate(count, rate_hz, seed, start_s):
    rng = random.Random(seed)
    rows = []
    for k in range(count):
        rows.append([start_s + k / rate_hz,
                     rng.gauss(0.0, 1e-3), rng.gauss(0.0, 1e-3), rng.gauss(7.29e-5, 1e-3),
                     rng.gauss(0.0, 0.02), rng.gauss(0.0, 0.02), rng.gauss(9.81, 0.02)])
    return rows


def imu_message(row, seq, frame_id, zero_stamp):
    msg = Imu()
    msg.header.seq = seq
    msg.header.frame_id = frame_id
    msg.header.stamp = rospy.Time(0, 0) if zero_stamp else ros_time(row[0])
    msg.orientation_covariance[0] = -1.0  # no orientation (REP 145)
    msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z = row[1:4]
    (msg.linear_acceleration.x, msg.linear_acceleration.y,
     msg.linear_acceleration.z) = row[4:7]
    return msg


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("bag", help="the bag to write")
    source = parser.add_mutually_exclusive_group(required=True)
    source.add_argument("--csv", help="truth: stamp_s,gx,gy,gz,ax,ay,az per message")
    source.add_argument("--generate", type=int, metavar="N", help="N generated messages")
    parser.add_argument("--rate-hz", type=float, default=400.0)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--start-s", type=float, default=1.7e9, help="first stamp (generate)")
    parser.add_argument("--truth", help="with --generate: write the truth CSV here")
    parser.add_argument("--topic", default="/imu")
    parser.add_argument("--frame-id", default="imu_link")
    parser.add_argument("--second-imu-topic", help="also write the messages on this topic")
    parser.add_argument("--string-topic", help="also write a std_msgs/String topic")
    parser.add_argument("--compression", choices=["none", "bz2", "lz4"], default="none")
    parser.add_argument("--zero-stamps", action="store_true",
                        help="header stamps zero; the receive times are the truth's stamps")
    parser.add_argument("--receive-delay-s", type=float, default=0.0005,
                        help="receive time minus stamp (the recorder's delay)")
    args = parser.parse_args()

    if args.csv:
        rows = read_truth(args.csv)
    else:
        rows = generate(args.generate, args.rate_hz, args.seed, args.start_s)
        if args.truth:
            with open(args.truth, "w", newline="") as f:
                writer = csv.writer(f)
                writer.writerow(["stamp_s", "gx", "gy", "gz", "ax", "ay", "az"])
                for row in rows:
                    writer.writerow([repr(x) for x in row])

    with rosbag.Bag(args.bag, "w", compression=args.compression) as bag:
        for seq, row in enumerate(rows):
            received = ros_time(row[0] + (0.0 if args.zero_stamps else args.receive_delay_s))
            msg = imu_message(row, seq, args.frame_id, args.zero_stamps)
            bag.write(args.topic, msg, received)
            if args.second_imu_topic:
                bag.write(args.second_imu_topic, msg, received)
            if args.string_topic and seq % 100 == 0:
                bag.write(args.string_topic, String(data=f"status {seq}"), received)
    return 0


if __name__ == "__main__":
    sys.exit(main())
