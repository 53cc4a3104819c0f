#include "slamkit/io/mrclam_reader.hpp"

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "common/temp_dir.hpp"
#include "slamkit/io/error.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

const fs::path kDataset6 = fs::path(SLAMKIT_DATASETS_DIR) / "mrclam" / "MRCLAM_Dataset6";

// A two-robot folder, each file as given (defaults: a small valid recording).
class MrclamFolder : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    files_ = {
        {"Barcodes.dat", "# Subject # Barcode #\n1 5\n2 14\n6 63\n7 81\n"},
        {"Landmark_Groundtruth.dat", "# header\n6 1.0 2.0 0.001 0.001\n7 -1.0 3.0 0.001 0.001\n"},
        {"Robot1_Odometry.dat", "# t v w\n100.0 0.1 0.0\n100.5 0.1 0.2\n101.0 0.0 0.0\n"},
        {"Robot1_Measurement.dat", "100.2 63 2.0 0.5\n100.4 14 1.5 -0.2\n100.6 99 3.0 0.1\n"},
        {"Robot1_Groundtruth.dat", "99.9 0.0 0.0 0.0\n100.6 0.05 0.0 0.0\n"},
        {"Robot2_Odometry.dat", "100.1 0.2 0.0\n100.8 0.0 0.0\n"},
        {"Robot2_Measurement.dat", "100.3 5 1.5 3.0\n100.7 81 2.5 0.0\n"},
        {"Robot2_Groundtruth.dat", "100.0 1.5 0.0 3.1\n100.9 1.6 0.0 3.1\n"},
    };
  }
  void Write() {
    for (const auto& [name, text] : files_) WriteFile(name, text);
  }
  // The InputError message of reading the folder with `name` replaced by `text`.
  std::string ErrorWith(const std::string& name, const std::string& text) {
    files_[name] = text;
    Write();
    try {
      ReadMrclam(dir_);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }

  std::map<std::string, std::string> files_;
};

TEST_F(MrclamFolder, MapsBarcodesToSubjectsAndCountsUnknownOnes) {
  Write();
  const MrclamDataset data = ReadMrclam(dir_);
  ASSERT_EQ(data.robots.size(), 2u);
  ASSERT_EQ(data.landmarks.size(), 2u);
  EXPECT_EQ(data.landmarks.at(7), Eigen::Vector2d(-1.0, 3.0));
  const MrclamRobot& r1 = data.robots[0];
  EXPECT_EQ(r1.odometry.size(), 3u);
  ASSERT_EQ(r1.sightings.size(), 2u);
  EXPECT_EQ(r1.sightings[0].subject, 6);  // barcode 63
  EXPECT_EQ(r1.sightings[1].subject, 2);  // barcode 14: robot 2
  EXPECT_EQ(r1.unknown_barcodes, 1);      // barcode 99
  EXPECT_EQ(data.robots[1].sightings[0].subject, 1);
}

TEST_F(MrclamFolder, TheFleetMergesTheRobotsInTimeOrderWithSightingsBeforeControls) {
  files_["Robot2_Odometry.dat"] = "100.2 0.2 0.0\n100.8 0.0 0.0\n";  // at Robot1's sighting time
  Write();
  // Not a structured binding: clang 14 cannot capture one in the lambda below.
  const std::pair<FleetLog, FleetTruth> fleet = MrclamFleet(ReadMrclam(dir_), {});
  const FleetLog& log = fleet.first;
  const FleetTruth& truth = fleet.second;
  ASSERT_EQ(log.vehicles, 2);
  EXPECT_EQ(log.start_poses[1].translation(), Eigen::Vector2d(1.5, 0.0));
  for (std::size_t i = 1; i < log.events.size(); ++i) {
    EXPECT_LE(log.events[i - 1].t_s, log.events[i].t_s) << i;
  }
  // At 100.2 s robot 1 sights landmark 6 and robot 2's control starts: the sighting first.
  const auto at = [&](double t, FleetEvent::Kind kind) {
    for (std::size_t i = 0; i < log.events.size(); ++i) {
      if (log.events[i].t_s == t && log.events[i].kind == kind) return int(i);
    }
    return -1;
  };
  EXPECT_LT(at(100.2, FleetEvent::Kind::kLandmarkSighting), at(100.2, FleetEvent::Kind::kControl));
  const FleetEvent& vv = log.events[at(100.4, FleetEvent::Kind::kVehicleSighting)];
  EXPECT_EQ(vv.vehicle, 0);
  EXPECT_EQ(vv.target, 1);
  // Robot 1's second control holds until its third record: 0.5 s.
  const FleetEvent& u = log.events[at(100.5, FleetEvent::Kind::kControl)];
  EXPECT_DOUBLE_EQ(u.dt_s, 0.5);
  EXPECT_EQ(u.value, Eigen::Vector2d(0.1, 0.2));
  EXPECT_EQ(truth.world.landmarks.size(), 2u);
}

TEST_F(MrclamFolder, ASelectionRenumbersTheVehiclesAndDropsRobotsLeftOut) {
  Write();
  MrclamSelection only_two;
  only_two.robots = {2};
  only_two.start_s = 0.05;  // after robot 2's first record at 100.1 s … from 100.15 s
  only_two.duration_s = 0.5;
  const auto [log, truth] = MrclamFleet(ReadMrclam(dir_), only_two);
  ASSERT_EQ(log.vehicles, 1);
  for (const FleetEvent& e : log.events) {
    EXPECT_EQ(e.vehicle, 0);
    EXPECT_NE(e.kind, FleetEvent::Kind::kVehicleSighting);  // robot 1 is not in the run
    EXPECT_GE(e.t_s, 100.15 - 1e-9);
    EXPECT_LT(e.t_s + e.dt_s, 100.65 + 1e-9);
  }
  EXPECT_NEAR(log.events.front().t_s, 100.15, 1e-9);  // the control active at the start, clipped
  const MrclamDataset data = ReadMrclam(dir_);
  MrclamSelection bad;
  bad.robots = {3};
  EXPECT_THROW(MrclamFleet(data, bad), InputError);
  bad.robots = {1, 1};
  EXPECT_THROW(MrclamFleet(data, bad), InputError);
  bad.robots = {};
  bad.start_s = 50.0;
  EXPECT_THROW(MrclamFleet(data, bad), InputError);
}

TEST_F(MrclamFolder, BadFilesNameTheFileTheLineAndTheField) {
  const struct {
    const char* file;
    const char* text;
    const char* expected;
  } cases[] = {
      {"Robot1_Odometry.dat", "100.0 0.1 0.0\n100.5 0.1\n", "Robot1_Odometry.dat:2: field 'angular velocity': missing"},
      {"Robot1_Odometry.dat", "100.0 0.1 0.0\n99.5 0.1 0.0\n", "Robot1_Odometry.dat:2: field 'time': 99.5 is earlier"},
      {"Robot1_Odometry.dat", "100.0 nan 0.0\n", "Robot1_Odometry.dat:1: field 'forward velocity': not a finite number"},
      {"Robot1_Measurement.dat", "# c\n100.2 63 -2.0 0.5\n", "Robot1_Measurement.dat:2: field 'range': -2.0 is outside"},
      {"Robot1_Measurement.dat", "100.2 63 2.0 0.5 7\n", "Robot1_Measurement.dat:1: a line has 5 fields, expected 4"},
      {"Robot1_Measurement.dat", "100.2 6x3 2.0 0.5\n", "Robot1_Measurement.dat:1: field 'barcode': not an integer"},
      {"Robot1_Measurement.dat", "100.2 63 2.0 45.0\n", "Robot1_Measurement.dat:1: field 'bearing'"},
      {"Robot2_Groundtruth.dat", "100.0 1.5 0.0 3.1\n100.9 1.6 0.0\n", "Robot2_Groundtruth.dat:2: field 'orientation': missing"},
      {"Barcodes.dat", "1 5\n2 5\n", "Barcodes.dat:2: field 'barcode': barcode 5 is mapped twice"},
      {"Barcodes.dat", "1 5\n2 14\n6 63\n7 81\n30 99\n", "Robot1_Measurement.dat:3: field 'barcode': barcode 99 is subject 30, neither"},
      {"Landmark_Groundtruth.dat", "6 1.0 2.0 0.001\n", "Landmark_Groundtruth.dat:1: field 'y std-dev': missing"},
      {"Robot2_Odometry.dat", "# only a comment\n", "robot 2 has no odometry"},
  };
  for (const auto& c : cases) {
    SetUp();
    EXPECT_NE(ErrorWith(c.file, c.text).find(c.expected), std::string::npos)
        << c.file << ": " << ErrorWith(c.file, c.text);
  }
}

TEST_F(MrclamFolder, AMissingFileOrAnotherFolderIsNamed) {
  Write();
  fs::remove(dir_ / "Robot2_Measurement.dat");
  EXPECT_THROW(
      {
        try {
          ReadMrclam(dir_);
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("Robot2_Measurement.dat: missing"), std::string::npos)
              << e.what();
          throw;
        }
      },
      InputError);
  fs::remove(dir_ / "Robot1_Odometry.dat");
  EXPECT_THROW(ReadMrclam(dir_), InputError);
  EXPECT_THROW(ReadMrclam(dir_ / "nothing"), InputError);
}

TEST(MrclamDataset6, HasFiveRobotsFifteenLandmarksAndEveryRecord) {
  if (!fs::exists(kDataset6 / "Barcodes.dat")) GTEST_SKIP() << "no " << kDataset6;
  const MrclamDataset data = ReadMrclam(kDataset6);
  ASSERT_EQ(data.robots.size(), 5u);
  EXPECT_EQ(data.landmarks.size(), 15u);
  // Every line below the four-line header is a record: odometry and ground truth whole, the
  // sightings kept or counted as unknown barcodes.
  const auto records = [](const fs::path& path) {
    std::ifstream in(path);
    int lines = 0;
    for (std::string line; std::getline(in, line);) lines += line.empty() || line[0] == '#' ? 0 : 1;
    return lines;
  };
  int unknown = 0;
  for (int n = 1; n <= 5; ++n) {
    const MrclamRobot& r = data.robots[n - 1];
    const std::string stem = "Robot" + std::to_string(n) + "_";
    EXPECT_EQ(int(r.odometry.size()), records(kDataset6 / (stem + "Odometry.dat")));
    EXPECT_EQ(int(r.truth.size()), records(kDataset6 / (stem + "Groundtruth.dat")));
    EXPECT_EQ(int(r.sightings.size()) + r.unknown_barcodes,
              records(kDataset6 / (stem + "Measurement.dat")));
    unknown += r.unknown_barcodes;
  }
  EXPECT_GT(unknown, 0);   // barcodes 34, 43 and 50 are misreads
  EXPECT_LT(unknown, 10);
  const auto [log, truth] = MrclamFleet(data, {});
  EXPECT_EQ(log.vehicles, 5);
  int vv = 0;
  for (const FleetEvent& e : log.events) vv += e.kind == FleetEvent::Kind::kVehicleSighting;
  EXPECT_GT(vv, 1000);  // the robots see each other often
}

}  // namespace
}  // namespace slamkit
