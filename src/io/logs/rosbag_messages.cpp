// C++17 (see rosbag_messages.hpp).
#include "rosbag_messages.hpp"

#include <cmath>
#include <set>
#include <sstream>

#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_msgs/TFMessage.h>

namespace slamkit::io_detail {
namespace {

double Yaw(const geometry_msgs::Quaternion& q) {
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

// The bag's topics with their types, for a message that names what is there.
std::string TopicList(rosbag::Bag& bag) {
  std::set<std::string> topics;
  rosbag::View all(bag);
  for (const rosbag::ConnectionInfo* c : all.getConnections()) {
    topics.insert(c->topic + " (" + c->datatype + ")");
  }
  std::ostringstream out;
  for (const std::string& t : topics) out << (out.tellp() > 0 ? ", " : "") << t;
  return topics.empty() ? "nothing" : out.str();
}

// That `topic` is in the bag and holds `type` only.
void CheckTopic(rosbag::Bag& bag, const std::string& topic, const std::string& type) {
  rosbag::View all(bag);
  bool found = false;
  for (const rosbag::ConnectionInfo* c : all.getConnections()) {
    if (c->topic != topic) continue;
    found = true;
    if (c->datatype != type) {
      throw BagError("topic " + topic + " holds " + c->datatype + ", not " + type);
    }
  }
  if (!found) throw BagError("no topic " + topic + " (the bag has: " + TopicList(bag) + ")");
}

void ReadTransforms(rosbag::Bag& bag, BagContents& out) {
  rosbag::View view(bag, rosbag::TopicQuery(std::vector<std::string>{"/tf", "/tf_static"}));
  for (const rosbag::MessageInstance& m : view) {
    const auto tf = m.instantiate<tf2_msgs::TFMessage>();
    if (!tf) continue;  // another type on /tf: not a transform
    for (const geometry_msgs::TransformStamped& t : tf->transforms) {
      const geometry_msgs::Vector3& p = t.transform.translation;
      out.transforms.push_back(
          {{t.header.stamp.toSec(), p.x, p.y, Yaw(t.transform.rotation)}, t.header.frame_id,
           t.child_frame_id});
    }
  }
}

void ReadOdometry(rosbag::Bag& bag, const std::string& topic, BagContents& out) {
  CheckTopic(bag, topic, "nav_msgs/Odometry");
  rosbag::View view(bag, rosbag::TopicQuery(topic));
  for (const rosbag::MessageInstance& m : view) {
    const auto odom = m.instantiate<nav_msgs::Odometry>();
    const geometry_msgs::Pose& pose = odom->pose.pose;
    out.odometry.push_back(
        {odom->header.stamp.toSec(), pose.position.x, pose.position.y, Yaw(pose.orientation)});
  }
}

void ReadScans(rosbag::Bag& bag, const std::string& topic, BagContents& out) {
  CheckTopic(bag, topic, "sensor_msgs/LaserScan");
  rosbag::View view(bag, rosbag::TopicQuery(topic));
  for (const rosbag::MessageInstance& m : view) {
    const auto msg = m.instantiate<sensor_msgs::LaserScan>();
    out.scans.push_back({msg->header.stamp.toSec(), msg->header.frame_id, msg->angle_min,
                         msg->angle_increment, msg->range_min, msg->range_max, msg->ranges});
  }
}

}  // namespace

BagContents ReadBagContents(const std::string& path, const std::string& scan_topic,
                            const std::string& odom_topic, bool read_odometry) {
  BagContents out;
  try {
    rosbag::Bag bag;
    bag.open(path, rosbag::bagmode::Read);
    ReadTransforms(bag, out);
    if (read_odometry) ReadOdometry(bag, odom_topic, out);
    ReadScans(bag, scan_topic, out);
  } catch (const rosbag::BagException& e) {
    throw BagError(std::string("not a readable ROS 1 bag: ") + e.what());
  } catch (const ros::Exception& e) {  // a message that does not deserialise
    throw BagError(std::string("a message cannot be read: ") + e.what());
  }
  return out;
}

}  // namespace slamkit::io_detail
