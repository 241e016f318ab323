// A fresh folder under the system temp directory, removed with everything in it at the end: as an
// object (TempDir) or as a test fixture (TempDirTest); and whole-file byte reads and writes.
#pragma once
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <string_view>
#include <vector>

namespace sao::test {

class TempDir {
 public:
  // Named after the running test, the process and a random number: parallel runs and two folders
  // in one test never meet.
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "sao_" + (info ? std::string(info->test_suite_name()) + "_" + info->name() : std::string("x")) +
                       "_" + std::to_string(::getpid()) + "_" + std::to_string(std::random_device{}());
    for (char& c : name)
      if (c == '/') c = '_';  // parameterised test names
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string file(std::string_view name) const { return (path_ / name).string(); }
  // Writes `bytes` to file(name) and returns its path.
  std::string write(std::string_view name, std::string_view bytes) const {
    const std::string p = file(name);
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    EXPECT_TRUE(out.good()) << p;
    return p;
  }

 private:
  std::filesystem::path path_;
};

// The whole file as bytes (empty when it cannot be read).
inline std::vector<char> readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Writes `bytes` to `path`, replacing what was there.
inline void writeBytes(const std::string& path, const std::vector<char>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

// A fixture whose every test has its own TempDir.
class TempDirTest : public ::testing::Test {
 protected:
  std::string file(std::string_view name) const { return tmp_.file(name); }

  TempDir tmp_;
};

}  // namespace sao::test
