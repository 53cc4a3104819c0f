#include "slamkit/io/atomic_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "common/temp_dir.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

class AtomicFile : public testing::TempDirTest {
 protected:

  int FilesInDir() const {
    int n = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir_)) ++n;
    return n;
  }
};

TEST_F(AtomicFile, WritesContentAndLeavesNoTemporary) {
  const fs::path path = dir_ / "out.txt";
  WriteFileAtomically(path, [](std::ostream& out) { out << "hello\n" << 42 << '\n'; });
  EXPECT_EQ(testing::ReadText(path), "hello\n42\n");
  WriteFileAtomically(path, std::string_view("replaced"));
  EXPECT_EQ(testing::ReadText(path), "replaced");
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
  EXPECT_EQ(testing::ReadText(path), "old");
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
