// Where sao-render writes. Every output is first written into a staging folder beside its final
// place; only a run that wrote everything moves it there, so a failed run leaves nothing behind
// and a new run never mixes its files with an earlier run's. An existing folder is replaced only
// when it is empty or an earlier sao-render output holding nothing but the files its manifest
// (sao-render-outputs.txt) lists; any other file in it stops the run before rendering, so a file
// sao-render did not write is never deleted.
#pragma once
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "sao/status.h"

namespace sao::render {

inline constexpr const char* kManifestName = "sao-render-outputs.txt";

class OutputFolder {
 public:
  // Checks the folder at `path` (`option` names it in messages, e.g. "--out"), creates its missing
  // parent folders and the staging folder. IoError naming the path and the problem.
  static Status stage(const std::string& path, const std::string& option, std::unique_ptr<OutputFolder>& out);
  ~OutputFolder();  // unless committed: removes the staging folder and the parent folders it made
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::filesystem::path& path() const { return final_; }
  // Reserves `relative` ("ao.png", "passes/ao_raw.exr") and gives the staged path to write it to,
  // its sub-folders created. InvalidInput for a name reserved twice or leaving the folder.
  Status file(const std::string& relative, std::string& stagedPath);
  // Reserves a sub-folder for files named later: no file() may take its name or a name above it.
  Status folder(const std::string& relative);
  // Writes the manifest and moves the staging folder into place, replacing the earlier output.
  Status commit();

 private:
  OutputFolder() = default;
  std::filesystem::path final_, staging_;
  std::vector<std::filesystem::path> createdParents_;  // deepest last
  std::vector<std::string> files_, folders_;
  Status reserve(const std::string& relative, bool isFolder, std::filesystem::path& rel);
  bool committed_ = false;
};

// One file outside every output folder (--save-depth): written beside its place under a temporary
// name and renamed over it on commit. Its folder must exist, and the path must not be a folder.
class OutputFile {
 public:
  static Status stage(const std::string& path, const std::string& option, std::unique_ptr<OutputFile>& out);
  ~OutputFile();  // unless committed: removes the temporary file
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  const std::string& stagedPath() const { return staging_; }
  Status commit();

 private:
  OutputFile() = default;
  std::string final_, staging_;
  bool committed_ = false;
};

// `path` absolute and normalised, without a trailing separator.
std::filesystem::path normalizedPath(const std::string& path);

}  // namespace sao::render
