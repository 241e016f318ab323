// Where the sample programs write: one rule for every file or folder the user names (sao-render's
// --out, --dump-passes, --save-depth; sao-viewer's --screenshot; sao-bench's --out):
//  - an output is written under a new name beside its place and renamed into place only when it
//    is complete, so a failed run leaves nothing behind and never a half-written file;
//  - nothing the program did not write is replaced unless the user says so with --overwrite (the
//    same flag in every program); an output folder an earlier run of the program wrote, holding
//    nothing but the files its manifest (<program>-outputs.txt) lists, is replaced as a whole;
//  - a file's name must end in its format's extension (an EXR is never written as depth.png);
//  - an input is never written onto, nor an output folder made around one, --overwrite or not.
// Refusals come back as one-line Status messages naming the path, the rule and the fix:
// InvalidInput for what the options alone get wrong (a program's exit status 2), IoError for what
// is in the way on disk (exit status 1).
#pragma once
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "sao/status.h"

namespace sao::samples {

// The flag that lets an output replace what the program did not write: one name and meaning in
// every program (its --help text below).
inline constexpr const char* kOverwriteOption = "--overwrite";
inline constexpr const char* kOverwriteHelp =
    "let outputs replace existing files of the same names that this program did not write (an existing file "
    "given as an output file; in an output folder holding other files, those of the same names; the other "
    "files are kept). Never an input: writing onto one is refused even so";

// What every writer of one run must respect.
struct WriteRules {
  std::string program;  // "sao-render": the manifest's name and the messages
  bool overwrite = false;  // --overwrite given
  struct Input {
    std::string option, path;  // "--depth", "d.exr"
  };
  std::vector<Input> inputs;  // files the run reads: never written onto or replaced
  // Adds `path` as an input when it names an existing file (a built-in scene's name does not).
  void addInput(const std::string& option, const std::string& path);
};

// The format a file output holds: its extensions (".exr"), lower case, and its name for messages.
struct FileFormat {
  std::string name;                     // "an OpenEXR file"
  std::vector<std::string> extensions;  // {".exr"}
};
inline const FileFormat kExrFormat{"an OpenEXR file", {".exr"}};
inline const FileFormat kPngFormat{"a PNG file", {".png"}};

// InvalidInput unless `path` ends in one of the format's extensions (any case).
Status checkExtension(const std::string& path, const std::string& option, const std::string& program,
                      const FileFormat& format);

// "<program>-outputs.txt": the files of a run in its output folder.
std::string manifestName(const std::string& program);

class OutputFolder {
 public:
  // Checks the folder at `path` (`option` names it in messages, e.g. "--out"): missing, empty, an
  // earlier output of the program (only the files its manifest lists), or any folder with
  // rules.overwrite; never one that holds an input. Creates its missing parent folders and the
  // staging folder beside it.
  static Status stage(const std::string& path, const std::string& option, const WriteRules& rules,
                      std::unique_ptr<OutputFolder>& out);
  ~OutputFolder();  // unless committed: removes the staging folder and the parent folders it made
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::filesystem::path& path() const { return final_; }
  // The folder the run writes into (a program whose parts name their own files, sao-bench): every
  // file in it at commit() is the run's and is listed in the manifest.
  const std::filesystem::path& stagingPath() const { return staging_; }
  // Reserves `relative` ("ao.png", "passes/ao_raw.exr") and gives the staged path to write it to,
  // its sub-folders created. InvalidInput for a name reserved twice or leaving the folder.
  Status file(const std::string& relative, std::string& stagedPath);
  // Reserves a sub-folder for files named later: no file() may take its name or a name above it.
  Status folder(const std::string& relative);
  // Writes the manifest and moves the staged files into place: the folder is replaced as a whole
  // when it is (still) an earlier output; with --overwrite, otherwise, the run's files are moved in
  // one by one and the folder's other files kept.
  Status commit();

 private:
  OutputFolder() = default;
  std::filesystem::path final_, staging_;
  WriteRules rules_;
  std::vector<std::filesystem::path> createdParents_;  // deepest last
  std::vector<std::string> files_, folders_;
  Status reserve(const std::string& relative, bool isFolder, std::filesystem::path& rel);
  Status mergeInto();
  bool committed_ = false;
};

// One file outside every output folder (--save-depth, --screenshot): written beside its place
// under a temporary name and renamed into place on commit. Its name must end in the format's
// extension, its folder must exist, it must not be a folder or an input, and an existing file is
// replaced only with rules.overwrite (checked at stage() and again at commit()).
class OutputFile {
 public:
  static Status stage(const std::string& path, const std::string& option, const FileFormat& format,
                      const WriteRules& rules, std::unique_ptr<OutputFile>& out);
  // The checks of stage() alone, nothing created: for a program that writes much later.
  static Status check(const std::string& path, const std::string& option, const FileFormat& format,
                      const WriteRules& rules);
  ~OutputFile();  // unless committed: removes the temporary file
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  const std::string& stagedPath() const { return staging_; }
  Status commit();

 private:
  OutputFile() = default;
  std::string final_, staging_, where_;
  bool overwrite_ = false;
  bool committed_ = false;
};

// A folder written in place across runs (sao-bench --tune: tune.csv is appended and resumed): the
// checks of OutputFolder::stage (the folder may be missing, empty, an earlier output of the
// program, or any folder with --overwrite; it must not hold an input), the folder created and its
// manifest made to list `files` (relative names) before they are written.
Status prepareFolderInPlace(const std::string& path, const std::string& option, const WriteRules& rules,
                            const std::vector<std::string>& files);

// `text` written to a new file beside `path`, then renamed over it: for the files of a folder
// whose rule was checked (prepareFolderInPlace). IoError naming the path.
Status writeFileInPlace(const std::string& path, const std::string& text);

// `path` absolute and normalised, without a trailing separator.
std::filesystem::path normalizedPath(const std::string& path);

}  // namespace sao::samples
