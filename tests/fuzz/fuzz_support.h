// Shared by the fuzz targets: a per-process scratch folder (on tmpfs where there is one) that is
// removed at exit, and a failure macro that aborts with a message (a libFuzzer crash, a failed
// replay test).
#pragma once
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>

// SAO_FUZZ_CHECK(condition[, printf-format, args...])
#define SAO_FUZZ_CHECK(cond, ...)                                                      \
  do {                                                                                 \
    if (!(cond)) {                                                                     \
      std::fprintf(stderr, "%s:%d: invariant broken: %s\n", __FILE__, __LINE__, #cond); \
      ::sao::fuzz::note(__VA_ARGS__);                                                  \
      std::abort();                                                                    \
    }                                                                                  \
  } while (0)

namespace sao::fuzz {

inline void note() {}
inline void note(const char* text) { std::fprintf(stderr, "%s\n", text); }
template <class... Args>
void note(const char* format, Args... args) {
  std::fprintf(stderr, format, args...);
  std::fputc('\n', stderr);
}

inline const std::filesystem::path& scratchDir() {
  // Never destroyed (still reachable, so not a leak): the atexit handler may run after statics die.
  static const std::filesystem::path* dir = [] {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path base = fs::is_directory("/dev/shm", ec) && access("/dev/shm", W_OK) == 0 ? fs::path("/dev/shm")
                                                                                             : fs::temp_directory_path();
    // The pid padded to a fixed width: the path appears in messages, and a path of another
    // length could take other branches, so a fixed -seed would not give the same run everywhere.
    std::string pid = std::to_string(getpid());
    pid.insert(0, 12 - std::min<std::size_t>(pid.size(), 12), '_');  // ci/fuzz.sh reads it back after the last '_'
    auto* d = new fs::path(base / ("sao_fuzz_" + pid));
    fs::create_directories(*d);
    std::atexit([] {
      std::error_code e;
      std::filesystem::remove_all(scratchDir(), e);
    });
    return d;
  }();
  return *dir;
}

inline void writeFile(const std::filesystem::path& path, const void* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  SAO_FUZZ_CHECK(out.good(), "cannot write %s", path.c_str());
}

}  // namespace sao::fuzz
