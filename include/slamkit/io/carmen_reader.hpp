#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/trajectory.hpp"

namespace slamkit {

struct CarmenReadOptions {
  // Skip malformed lines (counting them) instead of failing on the first one.
  bool skip_bad_lines = false;
  // A record whose timestamp is earlier than the previous record of its stream (ODOM, or scans)
  // by more than this is malformed; smaller steps back are accepted and counted. Real logs need
  // the slack: intel.clf's clock jitters back by up to 0.9 s (602 ODOM, 631 FLASER records)
  // although its records are in causal order. A timestamp below 1e-6 s means "none" (the
  // GMapping-written logs put `ODOM ... 0 pippo 0`, or a denormal, after every scan): unchecked,
  // and the next record is checked against the last one that had a timestamp. Equal timestamps
  // (repeated scan or ODOM stamps) are in order.
  double max_time_step_back_s = 1.0;
  // Take LaserScan::odometry from the scan record's own odometry fields (FLASER odom_x odom_y
  // odom_theta, ROBOTLASER1 robot pose), the default; false interpolates the ODOM records at the
  // scan's timestamp instead. In intel.clf the fields are exactly the latest ODOM record before
  // the scan in the file, whereas interpolating by its jittery timestamps is off by more than
  // 17 cm or 6.7° for 1 % of the scans.
  bool odometry_from_scan_fields = true;
  // The laser's no-return range, when the user knows it better than the log: if set, every
  // scan's max_range_m (FLASER and ROBOTLASER1) is this, whatever the log says.
  std::optional<double> max_range_m;
};

// A CARMEN log: the scans in log order with the odometry at each scan's timestamp, the raw
// odometry records, and the PARAM settings. Where timestamps are monotonic (the default options
// ensure it, up to max_time_step_back_s, for the records that have one) log order is time order;
// a log without any timestamp (all 0) is read in log order.
struct CarmenLog {
  std::vector<LaserScan> scans;
  Trajectory odometry;                        // the ODOM records in log order
  std::map<std::string, std::string> params;  // PARAM name value (the last one of a name)
  int skipped_lines = 0;                      // with skip_bad_lines
  int time_steps_back = 0;                    // records accepted a little back in time
  long long no_return_beams = 0;              // readings at or beyond their scan's max range
  std::vector<std::string> notes;             // what the reader decided that a user should know
};

// Reads ODOM, FLASER, ROBOTLASER1 and PARAM records (other records, blank lines and `#` lines are
// ignored); gzip-compressed files (by content, not name) are read transparently. Throws
// InputError naming the file, line and field for a wrong beam count, a non-number, NaN/inf, or
// time going backwards, unless options.skip_bad_lines (then the line is skipped and counted).
// A missing, unreadable or truncated gzip file is an InputError naming the file, and so is a
// log without any FLASER or ROBOTLASER1 scan (empty, comments only, ODOM only, another format
// such as a ROS bag). Values checked for physical sense (InputError naming the field): ranges
// are non-negative; a scan has at least one beam; the field of view is in (0, 360] degrees;
// max ranges are positive; pose, odometry, offset, max-range and ROBOTLASER1 start_angle and
// angular_resolution values have magnitude at most 1e6 (metres or radians), timestamps at most
// 1e12 s.
//
// Scan geometry. FLASER: the field of view is PARAM laser_front_laser_fov (degrees as CARMEN
// documents, or radians when at most 2π, as in csail-corrected.log.gz), else π, centred on the
// heading: angle_min_rad = -fov/2; with n beams the increment is fov/n for even n (180 beams at
// 1°, the last one at +89°) and fov/(n-1) for odd n (181 or 361 beams, both ends included).
// max_range_m (the no-return range: a reading at or above it is no return) is, in this order:
// options.max_range_m when set; PARAM laser_front_laser_max_range, else robot_front_laser_max,
// from the PARAM records before the scan, unless more than 0.1 % of the readings of the scans it
// covers exceed it by over 1 cm (then it is not the laser's no-return range: edmonton's
// `robot_front_laser_max 10` under readings up to 51 m; a note says so); else derived from the
// log: the largest reading (as stored, a float) of all FLASER scans that no such PARAM covers. Lasers write their no-return value
// as that largest reading (81.83 in intel.clf, 81.91 in csail), so those beams become no-returns
// and every shorter one stays a return; in a log where every beam returned, only the beams at
// the largest reading are lost. Without any reading (no finite positive range) it is infinity.
// laser_offset is (PARAM robot_frontlaser_offset, 0, 0).
// logged_pose is the record's x y theta. ROBOTLASER1: angle_min_rad = start_angle, the increment
// is angular_resolution, max_range_m = max_range (or options.max_range_m), logged_pose is the
// robot pose and laser_offset the laser pose seen from the robot pose.
//
// Odometry at a scan: with ODOM records (and not odometry_from_scan_fields), linear interpolation
// between the ODOM records (ordered by timestamp, log order among equal ones) that bracket the
// scan's timestamp, the heading along the shorter arc; the first or last record's pose outside
// their span; at a timestamp that several records share, the last of them in the log. ODOM
// records without a timestamp (see max_time_step_back_s) cannot be placed in time and are not
// used (a note counts them). Without ODOM records, without any that has a timestamp (a note says
// so), or for a scan without a timestamp (a note counts them), the scan record's odometry fields.
CarmenLog ReadCarmenLog(const std::filesystem::path& path, const CarmenReadOptions& options = {});

}  // namespace slamkit
