#!/usr/bin/python3
"""Writes a CARMEN log's FLASER scans as a ROS 1 bag (Debian's python3-rosbag).

    /usr/bin/python3 scripts/ros/carmen_to_bag.py LOG OUT.bag [--max-scans N]
                     [--robotlaser-log OUT.clf]

The bag holds, for each scan, a sensor_msgs/LaserScan on /scan (frame `laser`) and a
nav_msgs/Odometry on /odom (odom -> base_link) at the scan's timestamp with the scan record's
odometry, and one /tf_static transform base_link -> laser (PARAM robot_frontlaser_offset). The
geometry follows slamkit's CARMEN reader: field of view PARAM laser_front_laser_fov (degrees, or
radians when at most 2 pi), else pi, centred; increment fov/n for even n, fov/(n-1) for odd n;
range_max PARAM laser_front_laser_max_range, else the largest reading of the scans written.

A LaserScan carries float32 angles and ranges and a ROS time of whole nanoseconds, so a bag
cannot hold a CARMEN log's doubles exactly. --robotlaser-log also writes the bag's content as a
CARMEN ROBOTLASER1 log (every number as the bag holds it, printed to round-trip): slamkit run on
that log and on the bag must give the same trajectory (tests/apps/bag_test.cpp).
"""
import argparse
import gzip
import math
import struct

import rosbag
import rospy
from geometry_msgs.msg import Quaternion, TransformStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from tf2_msgs.msg import TFMessage


def f32(x):
    """x rounded to float32, as a Python float (a double holding the float32 value)."""
    return struct.unpack("f", struct.pack("f", x))[0]


def read_flaser(path, max_scans):
    params, scans = {}, []
    opener = gzip.open if open(path, "rb").read(2) == b"\x1f\x8b" else open
    with opener(path, "rt") as log:
        for line in log:
            fields = line.split()
            if len(fields) >= 3 and fields[0] == "PARAM":
                params[fields[1]] = fields[2]
            elif fields and fields[0] == "FLASER":
                n = int(fields[1])
                ranges = [float(r) for r in fields[2:2 + n]]
                rest = fields[2 + n:]
                odom = tuple(float(v) for v in rest[3:6])
                scans.append((float(rest[6]), ranges, odom))
                if max_scans and len(scans) == max_scans:
                    break
    return params, scans


def quaternion(yaw):
    return Quaternion(0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0))


def yaw_of(q):
    """The heading slamkit's bag reader decodes (the same expression, evaluated the same way)."""
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def stamp(t):
    secs = int(math.floor(t))
    nsecs = int(round((t - secs) * 1e9))
    if nsecs >= 1000000000:
        secs, nsecs = secs + 1, nsecs - 1000000000
    return rospy.Time(secs, nsecs)


def to_sec(time):
    """ros::Time::toSec() in C++: sec + 1e-9 * nsec."""
    return float(time.secs) + 1e-9 * float(time.nsecs)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("log")
    parser.add_argument("bag")
    parser.add_argument("--max-scans", type=int, default=0)
    parser.add_argument("--robotlaser-log")
    args = parser.parse_args()
    params, scans = read_flaser(args.log, args.max_scans)
    if not scans:
        raise SystemExit(f"carmen_to_bag: no FLASER scan in {args.log}")
    fov = float(params.get("laser_front_laser_fov", math.pi))
    fov = fov if fov <= 2 * math.pi else math.radians(fov)
    offset = float(params.get("robot_frontlaser_offset", 0.0))
    range_max = float(params.get("laser_front_laser_max_range",
                                 max(max(r) for _, r, _ in scans)))
    lines = []
    with rosbag.Bag(args.bag, "w") as bag:
        static = TransformStamped()
        static.header.stamp = stamp(scans[0][0])
        static.header.frame_id, static.child_frame_id = "base_link", "laser"
        static.transform.translation.x = offset
        static.transform.rotation = quaternion(0.0)
        bag.write("/tf_static", TFMessage([static]), static.header.stamp)
        # A bag's messages are read in the order of the times they were recorded at: the log's
        # order, with the stamps (which jitter back in some logs) made strictly increasing.
        recorded = static.header.stamp
        for t, ranges, (ox, oy, oth) in scans:
            n = len(ranges)
            time = stamp(t)
            recorded = max(time, recorded + rospy.Duration(0, 1))
            odom = Odometry()
            odom.header.stamp, odom.header.frame_id, odom.child_frame_id = time, "odom", "base_link"
            odom.pose.pose.position.x, odom.pose.pose.position.y = ox, oy
            odom.pose.pose.orientation = quaternion(oth)
            bag.write("/odom", odom, recorded)
            scan = LaserScan()
            scan.header.stamp, scan.header.frame_id = time, "laser"
            scan.angle_increment = f32(fov / n if n % 2 == 0 else fov / (n - 1))
            scan.angle_min = f32(-fov / 2.0)
            scan.angle_max = f32(scan.angle_min + (n - 1) * scan.angle_increment)
            scan.range_min, scan.range_max = 0.0, f32(range_max)
            scan.ranges = [f32(r) for r in ranges]
            recorded += rospy.Duration(0, 1)
            bag.write("/scan", scan, recorded)
            yaw = yaw_of(odom.pose.pose.orientation)
            pose = f"{ox!r} {oy!r} {yaw!r}"
            laser = f"{(ox + offset * math.cos(yaw))!r} {(oy + offset * math.sin(yaw))!r} {yaw!r}"
            lines.append(" ".join(
                ["ROBOTLASER1 0", repr(scan.angle_min), repr(f32(fov)), repr(scan.angle_increment),
                 repr(scan.range_max), "0.0 0", str(n)] + [repr(r) for r in scan.ranges] +
                ["0", laser, pose, "0 0 0 0 0", repr(to_sec(time)), "bag", repr(to_sec(time))]))
    if args.robotlaser_log:
        with open(args.robotlaser_log, "w") as out:
            out.write("\n".join(lines) + "\n")
    print(f"carmen_to_bag: {len(scans)} scans -> {args.bag}")


if __name__ == "__main__":
    main()
