#include "output_writer.h"

#include <filesystem>
#include <fstream>
#include <set>

namespace sao::codegen {

namespace fs = std::filesystem;

namespace {

// The names an earlier run listed in `dir`'s manifest (none when it has none).
std::set<std::string> listedOutputs(const fs::path& dir) {
  std::set<std::string> names;
  std::ifstream in(dir / kOutputsManifest);
  std::string line;
  while (std::getline(in, line))
    if (!line.empty()) names.insert(line);
  return names;
}

// Why `path` may not be replaced, or empty when it may.
std::string refusal(const fs::path& path, const std::string& name, const std::set<std::string>& listed,
                    const WriteRules& rules) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(path, ec))) return {};
  for (const std::string& input : rules.inputs)
    if (fs::equivalent(path, input, ec))
      return "'" + path.string() + "' is the input '" + input + "': an input is never written onto, --overwrite or not";
  if (rules.overwrite || listed.count(name)) return {};
  return "'" + path.string() + "' exists and sao-shaderc did not write it (" + kOutputsManifest +
         " there does not list it): move it, choose another -o folder, or give --overwrite to replace it";
}

}  // namespace

std::string OutputSet::commit(const std::string& dir, const WriteRules& rules) const {
  std::error_code ec;
  const std::set<std::string> listed = listedOutputs(dir);
  for (const auto& [name, content] : files_)
    if (std::string why = refusal(fs::path(dir) / name, name, listed, rules); !why.empty()) return why;
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
  // What this run writes, and what earlier runs wrote that is still there: the folder's manifest.
  std::set<std::string> ours;
  for (const std::string& name : listed)
    if (fs::exists(fs::symlink_status(fs::path(dir) / name, ec))) ours.insert(name);
  for (const auto& [name, content] : files_) ours.insert(name);
  {
    std::ofstream manifest(staging / kOutputsManifest, std::ios::binary);
    for (const std::string& name : ours) manifest << name << "\n";
    if (!manifest.good()) {
      fs::remove_all(staging, ec);
      return "cannot write '" + (fs::path(dir) / kOutputsManifest).string() + "'";
    }
  }
  for (const auto& [name, content] : files_) {
    fs::rename(staging / name, fs::path(dir) / name, ec);
    if (ec) {
      fs::remove_all(staging, ec);
      return "cannot move '" + name + "' into '" + dir + "': " + ec.message();
    }
  }
  fs::rename(staging / kOutputsManifest, fs::path(dir) / kOutputsManifest, ec);
  if (ec) {
    fs::remove_all(staging, ec);
    return "cannot move '" + std::string(kOutputsManifest) + "' into '" + dir + "': " + ec.message();
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
