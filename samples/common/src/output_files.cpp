#include "sao/samples/output_files.h"

#include <stdio.h>  // renameat2 (glibc, _GNU_SOURCE)
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <fstream>
#include <set>

namespace sao::samples {
namespace fs = std::filesystem;
namespace {

Status ioError(const std::string& message) { return Status::error(StatusCode::IoError, message); }
Status optionError(const std::string& message) { return Status::error(StatusCode::InvalidInput, message); }

// A manifest entry the program could have written: relative, inside the folder.
bool isPlainRelative(const fs::path& p) {
  if (p.empty() || p.is_absolute()) return false;
  for (const auto& part : p)
    if (part == ".." || part == "." || part.empty()) return false;
  return true;
}

// The files an earlier run lists in its manifest; false when there is no manifest.
bool readManifest(const fs::path& folder, const std::string& manifest, std::set<fs::path>& files) {
  std::ifstream in(folder / manifest);
  if (!in) return false;
  std::string line;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#' && isPlainRelative(line)) files.insert(fs::path(line).lexically_normal());
  return true;
}

// Writes the manifest listing `files` (relative to `folder`) under a new name, then renames it into place.
Status writeManifest(const fs::path& folder, const std::string& program, const std::set<fs::path>& files) {
  const fs::path path = folder / manifestName(program), temp = folder / ("." + manifestName(program) + ".new");
  std::ofstream out(temp);
  out << "# Written by " << program << ": the files of its runs in this folder. The next run into it\n"
      << "# replaces these (and nothing else: a folder holding other files is refused without --overwrite).\n";
  for (const auto& f : files) out << f.string() << "\n";
  out.close();
  std::error_code ec;
  if (!out || (fs::rename(temp, path, ec), ec)) {
    fs::remove(temp, ec);
    return ioError("cannot write '" + path.string() + "'");
  }
  return Status::success();
}

// The regular files under `folder`, relative to it (the manifest left out).
std::set<fs::path> filesUnder(const fs::path& folder, const std::string& manifest) {
  std::set<fs::path> files;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(folder, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const fs::path rel = it->path().lexically_relative(folder);
    if (rel != manifest && it->is_regular_file(ec)) files.insert(rel);
  }
  return files;
}

// Whether `folder` may be replaced as a whole: empty, or an earlier output holding only what it lists.
Status checkReplaceable(const fs::path& folder, const std::string& where, const std::string& program) {
  std::error_code ec;
  if (fs::is_empty(folder, ec) && !ec) return Status::success();
  const std::string manifest = manifestName(program);
  std::set<fs::path> listed;
  if (!readManifest(folder, manifest, listed))
    return ioError(where + " is not empty and not an earlier " + program + " output (it has no " + manifest +
                   "): empty it, choose another folder, or give --overwrite to replace only the files of the same "
                   "names");
  std::set<fs::path> parents;  // folders that hold a listed file
  for (const auto& f : listed)
    for (fs::path p = f.parent_path(); !p.empty(); p = p.parent_path()) parents.insert(p);
  for (auto it = fs::recursive_directory_iterator(folder, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const fs::path rel = it->path().lexically_relative(folder);
    const auto status = it->symlink_status(ec);
    if (ec) break;
    const bool ours = rel == manifest || (fs::is_regular_file(status) && listed.count(rel)) ||
                      (fs::is_directory(status) && parents.count(rel));
    if (!ours)
      return ioError(where + " holds '" + rel.string() + "', which is not one of the files its " + manifest +
                     " lists (" + program + " did not write it): move it out, choose another folder, or give "
                     "--overwrite to replace only the files of the same names");
  }
  if (ec) return ioError(where + ": cannot list it: " + ec.message());
  return Status::success();
}

// Whether `inner` is `outer` or lies inside it, symbolic links resolved.
bool within(const fs::path& inner, const fs::path& outer) {
  std::error_code ec;
  const fs::path a = fs::weakly_canonical(inner, ec);
  if (ec) return false;
  const fs::path b = fs::weakly_canonical(outer, ec);
  if (ec) return false;
  const fs::path rel = a.lexically_relative(b);
  return !rel.empty() && *rel.begin() != "..";
}

// mkdtemp / mkstemp beside `final`: a hidden name that says whose it is.
fs::path tempName(const fs::path& final, const std::string& program, const char* kind) {
  return final.parent_path() / ("." + final.filename().string() + "." + program + "-" + kind + "-XXXXXX");
}

// Removes what an earlier run listed in `folder`, then the folder when that emptied it. A file
// put there after the check is left where it is (in the hidden folder), never deleted.
void removeEarlierOutput(const fs::path& folder, const std::string& program) {
  std::set<fs::path> listed;
  readManifest(folder, manifestName(program), listed);
  std::error_code ec;
  std::set<fs::path, std::greater<>> folders;  // deepest first
  for (const auto& f : listed) {
    if (fs::is_regular_file(fs::symlink_status(folder / f, ec))) fs::remove(folder / f, ec);
    for (fs::path p = f.parent_path(); !p.empty(); p = p.parent_path()) folders.insert(p);
  }
  fs::remove(folder / manifestName(program), ec);
  for (const auto& d : folders) fs::remove(folder / d, ec);  // only if empty
  fs::remove(folder, ec);
  if (fs::exists(folder, ec))
    std::fprintf(stderr, "%s: warning: files added to the output folder during the run are kept in '%s'\n",
                 program.c_str(), folder.c_str());
}

// What every output folder must be before a run writes it (see output_files.h).
Status checkFolder(const fs::path& folder, const std::string& where, const WriteRules& rules) {
  for (const auto& input : rules.inputs)
    if (within(input.path, folder))
      return optionError(where + " holds the input " + input.option + " '" + input.path +
                         "', and a run replaces the folder's files: choose another folder or move the input out "
                         "(inputs are never written onto, --overwrite or not)");
  std::error_code ec;
  const auto status = fs::symlink_status(folder, ec);
  if (fs::is_symlink(status)) return ioError(where + " is a symbolic link: give the folder it points to");
  if (fs::exists(status)) {
    if (!fs::is_directory(status)) return ioError(where + " exists and is not a folder");
    if (!rules.overwrite)
      if (Status s = checkReplaceable(folder, where, rules.program); !s) return s;
  }
  return Status::success();
}

mode_t currentUmask() {
  const mode_t m = ::umask(0);
  ::umask(m);
  return m;
}

// Renames `from` to `to` unless `to` exists (atomically where the file system can).
int renameNoReplace(const char* from, const char* to) {
  if (::renameat2(AT_FDCWD, from, AT_FDCWD, to, RENAME_NOREPLACE) == 0) return 0;
  if (errno != EINVAL && errno != ENOSYS && errno != ENOTSUP) return -1;
  struct stat st;
  if (::lstat(to, &st) == 0) {
    errno = EEXIST;
    return -1;
  }
  return ::rename(from, to);
}

}  // namespace

void WriteRules::addInput(const std::string& option, const std::string& path) {
  std::error_code ec;
  if (!path.empty() && fs::exists(path, ec) && !fs::is_directory(path, ec)) inputs.push_back({option, path});
}

std::string manifestName(const std::string& program) { return program + "-outputs.txt"; }

Status checkExtension(const std::string& path, const std::string& option, const std::string& program,
                      const FileFormat& format) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  for (const std::string& e : format.extensions)
    if (ext == e) return Status::success();
  std::string names;
  for (const std::string& e : format.extensions) names += (names.empty() ? "" : " or ") + e;
  const std::string example = fs::path(path).replace_extension(format.extensions.front()).string();
  return optionError(option + " '" + path + "': " + program + " writes " + format.name +
                     " there, so its name must end in " + names + ": give e.g. '" + example + "'");
}

fs::path normalizedPath(const std::string& path) {
  fs::path p = fs::absolute(path).lexically_normal();
  if (p.filename().empty() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
  return p;
}

Status OutputFolder::stage(const std::string& path, const std::string& option, const WriteRules& rules,
                           std::unique_ptr<OutputFolder>& out) {
  std::unique_ptr<OutputFolder> f(new OutputFolder);
  f->final_ = normalizedPath(path);
  f->rules_ = rules;
  const std::string where = option + " '" + path + "'";
  if (f->final_ == f->final_.root_path()) return ioError(where + ": the root folder cannot be an output folder");
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  if (!ec) {
    const fs::path rel = cwd.lexically_relative(f->final_);
    if (!rel.empty() && *rel.begin() != "..")
      return ioError(where + " is or holds the working folder, which a run replaces: choose another folder");
  }
  if (Status s = checkFolder(f->final_, where, rules); !s) return s;
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
  std::string name = tempName(f->final_, rules.program, "new").string();
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
  if (!isPlainRelative(rel) || rel == manifestName(rules_.program))
    return optionError("'" + relative + "' is not a name " + rules_.program + " can write in '" + final_.string() +
                       "'");
  auto inside = [](const fs::path& a, const fs::path& b) {  // a is b or lies inside it
    const fs::path r = a.lexically_relative(b);
    return !r.empty() && *r.begin() != "..";
  };
  auto clash = [&] {
    return optionError("two outputs would be written to '" + (final_ / rel).string() + "' (or inside it)");
  };
  for (const auto& f : files_)
    if (inside(rel, f) || inside(f, rel)) return clash();
  for (const auto& d : folders_)
    if (isFolder ? (inside(rel, d) || inside(d, rel)) : inside(d, rel)) return clash();
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

// --overwrite into a folder holding other files: each of the run's files renamed into place, the
// manifest then lists them and the earlier runs' files still there.
Status OutputFolder::mergeInto() {
  const std::string manifest = manifestName(rules_.program);
  std::set<fs::path> listed, kept;
  readManifest(final_, manifest, listed);
  std::error_code ec;
  for (const auto& rel : filesUnder(staging_, manifest)) {
    const fs::path target = final_ / rel;
    fs::create_directories(target.parent_path(), ec);
    if (ec) return ioError("cannot create the folder '" + target.parent_path().string() + "': " + ec.message());
    if (fs::is_directory(fs::symlink_status(target, ec)))
      return ioError("'" + target.string() + "' is a folder: " + rules_.program + " replaces files only");
    if (::rename((staging_ / rel).c_str(), target.c_str()) != 0)
      return ioError("cannot write '" + target.string() + "': " + std::strerror(errno));
    listed.insert(rel);
  }
  for (const auto& f : listed)
    if (fs::is_regular_file(fs::symlink_status(final_ / f, ec))) kept.insert(f);
  if (Status s = writeManifest(final_, rules_.program, kept); !s) return s;
  fs::remove_all(staging_, ec);
  return Status::success();
}

Status OutputFolder::commit() {
  const std::string manifest = manifestName(rules_.program);
  if (Status s = writeManifest(staging_, rules_.program, filesUnder(staging_, manifest)); !s) return s;
  std::error_code ec;
  const std::string where = "'" + final_.string() + "'";
  if (fs::exists(fs::symlink_status(final_, ec))) {
    // Checked again: a file put there while the run worked must survive.
    if (Status s = checkReplaceable(final_, "the output folder " + where, rules_.program); !s) {
      if (!rules_.overwrite) return s;
      if (Status m = mergeInto(); !m) return m;
      committed_ = true;
      return Status::success();
    }
    std::string old = tempName(final_, rules_.program, "old").string();
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
    removeEarlierOutput(old, rules_.program);
  } else if (::rename(staging_.c_str(), final_.c_str()) != 0) {
    return ioError("cannot move the outputs into " + where + ": " + std::strerror(errno));
  }
  committed_ = true;
  return Status::success();
}

Status OutputFile::check(const std::string& path, const std::string& option, const FileFormat& format,
                         const WriteRules& rules) {
  const fs::path final = normalizedPath(path);
  const std::string where = option + " '" + path + "'";
  std::error_code ec;
  if (fs::is_directory(final, ec)) return ioError(where + " is a folder");
  if (Status s = checkExtension(path, option, rules.program, format); !s) return s;
  if (!fs::is_directory(final.parent_path(), ec))
    return ioError(where + ": its folder '" + final.parent_path().string() + "' does not exist");
  for (const auto& input : rules.inputs)
    if (fs::equivalent(final, input.path, ec) && !ec)
      return optionError(where + " is the input " + input.option + " '" + input.path +
                         "' (the same file): an input is never written onto, --overwrite or not: give another name");
  if (fs::exists(fs::symlink_status(final, ec)) && !rules.overwrite)
    return ioError(where + " exists, and " + rules.program +
                   " replaces no file it did not write: give another name, or --overwrite to replace it");
  return Status::success();
}

Status OutputFile::stage(const std::string& path, const std::string& option, const FileFormat& format,
                         const WriteRules& rules, std::unique_ptr<OutputFile>& out) {
  if (Status s = check(path, option, format, rules); !s) return s;
  std::unique_ptr<OutputFile> f(new OutputFile);
  const fs::path final = normalizedPath(path);
  f->where_ = option + " '" + path + "'";
  std::string name = tempName(final, rules.program, "new").string();
  const int fd = ::mkstemp(name.data());
  if (fd < 0) return ioError(f->where_ + ": cannot create a file beside it: " + std::strerror(errno));
  ::fchmod(fd, 0666 & ~currentUmask());
  ::close(fd);
  f->final_ = final.string();
  f->staging_ = name;
  f->overwrite_ = rules.overwrite;
  out = std::move(f);
  return Status::success();
}

OutputFile::~OutputFile() {
  if (!committed_ && !staging_.empty()) ::unlink(staging_.c_str());
}

Status OutputFile::commit() {
  if (overwrite_ ? ::rename(staging_.c_str(), final_.c_str()) : renameNoReplace(staging_.c_str(), final_.c_str())) {
    if (errno == EEXIST)
      return ioError(where_ + " appeared while the run worked, and it is not replaced without --overwrite: nothing "
                              "was written there");
    return ioError("cannot write '" + final_ + "': " + std::strerror(errno));
  }
  committed_ = true;
  return Status::success();
}

Status prepareFolderInPlace(const std::string& path, const std::string& option, const WriteRules& rules,
                            const std::vector<std::string>& files) {
  const fs::path folder = normalizedPath(path);
  const std::string where = option + " '" + path + "'";
  if (Status s = checkFolder(folder, where, rules); !s) return s;
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) return ioError(where + ": cannot create it: " + ec.message());
  std::set<fs::path> listed, kept;
  readManifest(folder, manifestName(rules.program), listed);
  for (const auto& f : listed)
    if (fs::is_regular_file(fs::symlink_status(folder / f, ec))) kept.insert(f);
  for (const auto& f : files) kept.insert(fs::path(f).lexically_normal());
  return writeManifest(folder, rules.program, kept);
}

Status writeFileInPlace(const std::string& path, const std::string& text) {
  const fs::path final = normalizedPath(path);
  std::string name = (final.parent_path() / ("." + final.filename().string() + ".new-XXXXXX")).string();
  const int fd = ::mkstemp(name.data());
  if (fd < 0) return ioError("cannot write '" + path + "': " + std::strerror(errno));
  ::fchmod(fd, 0666 & ~currentUmask());
  bool ok = true;
  for (std::size_t done = 0; ok && done < text.size();) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    ok = n > 0;
    if (ok) done += std::size_t(n);
  }
  const int e = errno;
  if (::close(fd) != 0) ok = false;
  if (!ok || ::rename(name.c_str(), final.c_str()) != 0) {
    const int why = ok ? errno : e;
    ::unlink(name.c_str());
    return ioError("cannot write '" + path + "': " + std::strerror(why));
  }
  return Status::success();
}

}  // namespace sao::samples
