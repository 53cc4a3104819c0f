#include "slamkit/io/atomic_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace slamkit {
namespace {

namespace fs = std::filesystem;

class AtomicFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("slamkit_atomic_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  int FilesInDir() const {
    int n = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir_)) ++n;
    return n;
  }
  static std::string Read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }

  fs::path dir_;
};

TEST_F(AtomicFile, WritesContentAndLeavesNoTemporary) {
  const fs::path path = dir_ / "out.txt";
  WriteFileAtomically(path, [](std::ostream& out) { out << "hello\n" << 42 << '\n'; });
  EXPECT_EQ(Read(path), "hello\n42\n");
  WriteFileAtomically(path, std::string_view("replaced"));
  EXPECT_EQ(Read(path), "replaced");
  EXPECT_EQ(FilesInDir(), 1);
}

TEST_F(AtomicFile, ThrowingWriterLeavesNoFile) {
  const fs::path path = dir_ / "out.txt";
  try {
    WriteFileAtomically(path, [](std::ostream& out) {
      out << "partial";
      throw std::logic_error("boom");
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("boom"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_EQ(FilesInDir(), 0);
}

TEST_F(AtomicFile, ThrowingWriterKeepsTheOldFile) {
  const fs::path path = dir_ / "out.txt";
  WriteFileAtomically(path, std::string_view("old"));
  EXPECT_THROW(WriteFileAtomically(path, [](std::ostream&) { throw std::runtime_error("x"); }),
               std::runtime_error);
  EXPECT_EQ(Read(path), "old");
  EXPECT_EQ(FilesInDir(), 1);
}

TEST_F(AtomicFile, FailingStreamIsAnError) {
  const fs::path path = dir_ / "out.txt";
  EXPECT_THROW(
      WriteFileAtomically(path, [](std::ostream& out) { out.setstate(std::ios::failbit); }),
      std::runtime_error);
  EXPECT_EQ(FilesInDir(), 0);
}

TEST_F(AtomicFile, MissingDirectoryNamesThePath) {
  const fs::path path = dir_ / "no_such_dir" / "out.txt";
  try {
    WriteFileAtomically(path, std::string_view("x"));
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace slamkit
