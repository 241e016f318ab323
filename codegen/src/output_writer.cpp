#include "output_writer.h"

#include <filesystem>
#include <fstream>

namespace sao::codegen {

namespace fs = std::filesystem;

std::string OutputSet::commit(const std::string& dir) const {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return "cannot create output folder '" + dir + "': " + ec.message();
  const fs::path staging = fs::path(dir) / ".sao-shaderc-staging";
  fs::remove_all(staging, ec);
  fs::create_directories(staging, ec);
  if (ec) return "cannot create staging folder '" + staging.string() + "': " + ec.message();
  for (const auto& [name, content] : files_) {
    std::ofstream out(staging / name, std::ios::binary);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    if (!out.good()) {
      fs::remove_all(staging, ec);
      return "cannot write '" + (fs::path(dir) / name).string() + "'";
    }
  }
  for (const auto& [name, content] : files_) {
    fs::rename(staging / name, fs::path(dir) / name, ec);
    if (ec) {
      fs::remove_all(staging, ec);
      return "cannot move '" + name + "' into '" + dir + "': " + ec.message();
    }
  }
  fs::remove_all(staging, ec);
  return {};
}

std::string makeDepfile(const std::string& target, const std::vector<std::string>& deps) {
  auto escape = [](const std::string& s) {
    std::string out;
    for (char c : s) {
      if (c == ' ' || c == '#') out += '\\';
      if (c == '$') out += '$';
      out += c;
    }
    return out;
  };
  std::string text = escape(target) + ":";
  for (const auto& d : deps) text += " \\\n  " + escape(d);
  return text + "\n";
}

}  // namespace sao::codegen
