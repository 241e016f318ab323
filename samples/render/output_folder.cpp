#include "output_folder.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <fstream>
#include <set>

namespace sao::render {
namespace fs = std::filesystem;
namespace {

Status ioError(const std::string& message) { return Status::error(StatusCode::IoError, message); }

// A manifest entry sao-render could have written: relative, inside the folder.
bool isPlainRelative(const fs::path& p) {
  if (p.empty() || p.is_absolute()) return false;
  for (const auto& part : p)
    if (part == ".." || part == "." || part.empty()) return false;
  return true;
}

// The files an earlier run lists in its manifest; false when there is no manifest.
bool readManifest(const fs::path& folder, std::set<fs::path>& files) {
  std::ifstream in(folder / kManifestName);
  if (!in) return false;
  std::string line;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#' && isPlainRelative(line)) files.insert(fs::path(line).lexically_normal());
  return true;
}

// Whether `folder` may be replaced: empty, or an earlier output holding only what it lists.
Status checkReplaceable(const fs::path& folder, const std::string& where) {
  std::error_code ec;
  if (fs::is_empty(folder, ec) && !ec) return Status::success();
  std::set<fs::path> listed;
  if (!readManifest(folder, listed))
    return ioError(where + " is not empty and not an earlier sao-render output (it has no " + kManifestName +
                   "): empty it or choose another folder");
  std::set<fs::path> parents;  // folders that hold a listed file
  for (const auto& f : listed)
    for (fs::path p = f.parent_path(); !p.empty(); p = p.parent_path()) parents.insert(p);
  for (auto it = fs::recursive_directory_iterator(folder, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const fs::path rel = it->path().lexically_relative(folder);
    const auto status = it->symlink_status(ec);
    if (ec) break;
    const bool ours = rel == kManifestName || (fs::is_regular_file(status) && listed.count(rel)) ||
                      (fs::is_directory(status) && parents.count(rel));
    if (!ours)
      return ioError(where + " holds '" + rel.string() + "', which is not one of the files its " + kManifestName +
                     " lists (sao-render did not write it): move it out, or choose another folder");
  }
  if (ec) return ioError(where + ": cannot list it: " + ec.message());
  return Status::success();
}

// mkdtemp / mkstemp beside `final`: a hidden name that says whose it is.
fs::path tempName(const fs::path& final, const char* kind) {
  return final.parent_path() / ("." + final.filename().string() + ".sao-render-" + kind + "-XXXXXX");
}

// Removes what an earlier run listed in `folder`, then the folder when that emptied it. A file
// put there after the check is left where it is (in the hidden folder), never deleted.
void removeEarlierOutput(const fs::path& folder) {
  std::set<fs::path> listed;
  readManifest(folder, listed);
  std::error_code ec;
  std::set<fs::path, std::greater<>> folders;  // deepest first
  for (const auto& f : listed) {
    if (fs::is_regular_file(fs::symlink_status(folder / f, ec))) fs::remove(folder / f, ec);
    for (fs::path p = f.parent_path(); !p.empty(); p = p.parent_path()) folders.insert(p);
  }
  fs::remove(folder / kManifestName, ec);
  for (const auto& d : folders) fs::remove(folder / d, ec);  // only if empty
  fs::remove(folder, ec);
  if (fs::exists(folder, ec))
    std::fprintf(stderr, "sao-render: warning: files added to the output folder during the run are kept in '%s'\n",
                 folder.c_str());
}

mode_t currentUmask() {
  const mode_t m = ::umask(0);
  ::umask(m);
  return m;
}

}  // namespace

fs::path normalizedPath(const std::string& path) {
  fs::path p = fs::absolute(path).lexically_normal();
  if (p.filename().empty() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
  return p;
}

Status OutputFolder::stage(const std::string& path, const std::string& option, std::unique_ptr<OutputFolder>& out) {
  std::unique_ptr<OutputFolder> f(new OutputFolder);
  f->final_ = normalizedPath(path);
  const std::string where = option + " '" + path + "'";
  if (f->final_ == f->final_.root_path()) return ioError(where + ": the root folder cannot be an output folder");
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  if (!ec) {
    const fs::path rel = cwd.lexically_relative(f->final_);
    if (!rel.empty() && *rel.begin() != "..")
      return ioError(where + " is or holds the working folder, which a run replaces: choose another folder");
  }
  const auto status = fs::symlink_status(f->final_, ec);
  if (fs::is_symlink(status)) return ioError(where + " is a symbolic link: give the folder it points to");
  if (fs::exists(status)) {
    if (!fs::is_directory(status)) return ioError(where + " exists and is not a folder");
    if (Status s = checkReplaceable(f->final_, where); !s) return s;
  }
  // Missing parents: made now and removed again if the run fails.
  std::vector<fs::path> missing;
  for (fs::path p = f->final_.parent_path(); !fs::exists(p, ec); p = p.parent_path()) missing.push_back(p);
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    if (!fs::create_directory(*it, ec) || ec)
      return ioError(where + ": cannot create the folder '" + it->string() + "': " + ec.message());
    f->createdParents_.push_back(*it);
  }
  if (!fs::is_directory(f->final_.parent_path(), ec))
    return ioError(where + ": '" + f->final_.parent_path().string() + "' is not a folder");
  std::string name = tempName(f->final_, "new").string();
  if (!::mkdtemp(name.data()))
    return ioError(where + ": cannot create a folder beside it: " + std::strerror(errno));
  f->staging_ = name;
  ::chmod(name.c_str(), 0777 & ~currentUmask());  // mkdtemp makes it private; an output folder is not
  out = std::move(f);
  return Status::success();
}

OutputFolder::~OutputFolder() {
  if (committed_) return;
  std::error_code ec;
  if (!staging_.empty()) fs::remove_all(staging_, ec);
  for (auto it = createdParents_.rbegin(); it != createdParents_.rend(); ++it) fs::remove(*it, ec);  // if empty
}

Status OutputFolder::reserve(const std::string& relative, bool isFolder, fs::path& rel) {
  rel = fs::path(relative).lexically_normal();
  if (!isPlainRelative(rel) || rel == kManifestName)
    return Status::error(StatusCode::InvalidInput,
                         "'" + relative + "' is not a name sao-render can write in '" + final_.string() + "'");
  auto within = [](const fs::path& a, const fs::path& b) {  // a is b or lies inside it
    const fs::path r = a.lexically_relative(b);
    return !r.empty() && *r.begin() != "..";
  };
  auto clash = [&] {
    return Status::error(StatusCode::InvalidInput,
                         "two outputs would be written to '" + (final_ / rel).string() + "' (or inside it)");
  };
  for (const auto& f : files_)
    if (within(rel, f) || within(f, rel)) return clash();
  for (const auto& d : folders_)
    if (isFolder ? (within(rel, d) || within(d, rel)) : within(d, rel)) return clash();
  (isFolder ? folders_ : files_).push_back(rel.string());
  return Status::success();
}

Status OutputFolder::folder(const std::string& relative) {
  fs::path rel;
  return reserve(relative, true, rel);
}

Status OutputFolder::file(const std::string& relative, std::string& stagedPath) {
  fs::path rel;
  if (Status s = reserve(relative, false, rel); !s) return s;
  std::error_code ec;
  fs::create_directories((staging_ / rel).parent_path(), ec);
  if (ec) return ioError("cannot create a folder in '" + staging_.string() + "': " + ec.message());
  stagedPath = (staging_ / rel).string();
  return Status::success();
}

Status OutputFolder::commit() {
  std::error_code ec;
  {
    std::ofstream manifest(staging_ / kManifestName);
    manifest << "# Written by sao-render: the files of the run in this folder. The next run into it\n"
                "# replaces these (and nothing else: a folder holding other files is refused).\n";
    for (const auto& f : files_)
      if (fs::exists(staging_ / f, ec)) manifest << f << "\n";
    manifest.close();
    if (!manifest) return ioError("cannot write '" + (staging_ / kManifestName).string() + "'");
  }
  const std::string where = "'" + final_.string() + "'";
  if (fs::exists(fs::symlink_status(final_, ec))) {
    // Checked again: a file put there while the run rendered must survive.
    if (Status s = checkReplaceable(final_, "the output folder '" + final_.string() + "'"); !s) return s;
    std::string old = tempName(final_, "old").string();
    if (!::mkdtemp(old.data())) return ioError("cannot replace " + where + ": " + std::strerror(errno));
    if (::rename(final_.c_str(), old.c_str()) != 0) {
      const int e = errno;
      ::rmdir(old.c_str());
      return ioError("cannot replace " + where + ": " + std::strerror(e));
    }
    if (::rename(staging_.c_str(), final_.c_str()) != 0) {
      const int e = errno;
      ::rename(old.c_str(), final_.c_str());
      return ioError("cannot move the outputs into " + where + ": " + std::strerror(e));
    }
    removeEarlierOutput(old);
  } else if (::rename(staging_.c_str(), final_.c_str()) != 0) {
    return ioError("cannot move the outputs into " + where + ": " + std::strerror(errno));
  }
  committed_ = true;
  return Status::success();
}

Status OutputFile::stage(const std::string& path, const std::string& option, std::unique_ptr<OutputFile>& out) {
  std::unique_ptr<OutputFile> f(new OutputFile);
  const fs::path final = normalizedPath(path);
  const std::string where = option + " '" + path + "'";
  std::error_code ec;
  if (fs::is_directory(final, ec)) return ioError(where + " is a folder");
  if (!fs::is_directory(final.parent_path(), ec))
    return ioError(where + ": its folder '" + final.parent_path().string() + "' does not exist");
  std::string name = tempName(final, "new").string();
  const int fd = ::mkstemp(name.data());
  if (fd < 0) return ioError(where + ": cannot create a file beside it: " + std::strerror(errno));
  ::fchmod(fd, 0666 & ~currentUmask());
  ::close(fd);
  f->final_ = final.string();
  f->staging_ = name;
  out = std::move(f);
  return Status::success();
}

OutputFile::~OutputFile() {
  if (!committed_ && !staging_.empty()) ::unlink(staging_.c_str());
}

Status OutputFile::commit() {
  if (::rename(staging_.c_str(), final_.c_str()) != 0)
    return ioError("cannot write '" + final_ + "': " + std::strerror(errno));
  committed_ = true;
  return Status::success();
}

}  // namespace sao::render
