// Private to slamkit_io: what the bag reader takes from a ROS 1 bag, as plain data. The file that
// reads the messages (rosbag_messages.cpp) is compiled as C++17, because ROS 1's generated
// message headers use std::allocator<void>::rebind, which C++20 removed; so this header includes
// nothing of slamkit's.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace slamkit::io_detail {

struct BagScan {
  double t_s = 0.0;  // header stamp, as ros::Time::toSec()
  std::string frame;
  float angle_min = 0.0f, angle_increment = 0.0f, range_min = 0.0f, range_max = 0.0f;
  std::vector<float> ranges;
};

struct BagPose {
  double t_s = 0.0;
  double x = 0.0, y = 0.0, yaw = 0.0;
};

struct BagTransform {
  BagPose pose;
  std::string parent, child;  // frame names as written
};

struct BagContents {
  std::vector<BagScan> scans;          // bag order
  std::vector<BagPose> odometry;       // bag order (with read_odometry)
  std::vector<BagTransform> transforms;  // /tf and /tf_static, bag order
};

// A bag that cannot be read, or a topic that is missing or of another type; the message names
// the reason, not the file.
struct BagError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The scans of `scan_topic` (sensor_msgs/LaserScan), the odometry of `odom_topic`
// (nav_msgs/Odometry) when `read_odometry`, and every transform of /tf and /tf_static.
BagContents ReadBagContents(const std::string& path, const std::string& scan_topic,
                            const std::string& odom_topic, bool read_odometry);

}  // namespace slamkit::io_detail
