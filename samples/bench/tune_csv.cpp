#include "tune_csv.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "sao/samples/output_files.h"
#include "tune_grid.h"

namespace sao::bench {
namespace {

// With the objective (a), the header gains a_rays and names the error column rmse_vs_a: a file of
// one objective is refused by a tune of the other. Without the session column: the format before it.
std::string headerWithoutSession(const std::vector<std::string>& scenes, std::uint32_t objectiveRays) {
  std::string h = "kind,name,backend,depth,inputs,size,converged_taps,own_converged_frames";
  if (objectiveRays) h += ",a_rays";
  for (const std::string& s : kTunedSettings) h += "," + s;
  h += ",runs";
  for (const std::string& scene : scenes)
    for (const std::string c : {"ms", objectiveRays ? "rmse_vs_a" : "rmse_vs_c", "blotch", "highfreq", "silhouette"})
      h += "," + scene + "_" + c;
  return h;
}

std::string header(const std::vector<std::string>& scenes, std::uint32_t objectiveRays) {
  return headerWithoutSession(scenes, objectiveRays) + ",session";
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

std::string number(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}

bool parseNumber(const std::string& text, double& out) {
  if (text.empty()) return false;
  char* end = nullptr;
  out = std::strtod(text.c_str(), &end);
  return *end == 0;
}

bool parseWhole(const std::string& text, std::uint32_t& out) {
  double v;
  if (!parseNumber(text, v) || v < 0 || v > 4294967295.0 || std::floor(v) != v) return false;
  out = std::uint32_t(v);
  return true;
}

}  // namespace

std::string TuneRow::columns() const {
  std::string k = kind + "," + name + "," + backend + "," + depth + "," + inputs + "," + std::to_string(size.width) + "x" +
                  std::to_string(size.height) + "," + std::to_string(convergedTaps) + "," + std::to_string(ownConvergedFrames);
  if (objectiveRays) k += "," + std::to_string(objectiveRays);
  for (const std::string& s : kTunedSettings) k += "," + tunedSettingValue(settings, s);
  return k;
}

std::string TuneRow::key() const {
  return isTimeAnchor(kind, name) ? columns() + " session " + std::to_string(session) : columns();
}

double TuneRow::totalMs() const {
  double t = 0;
  for (const SceneFigures& s : scenes) t += s.ms;
  return t;
}

double TuneRow::meanRmse() const {
  double e = 0;
  for (const SceneFigures& s : scenes) e += s.rmse;
  return scenes.empty() ? NAN : e / double(scenes.size());
}

double TuneRow::meanBlotch() const {
  double e = 0;
  for (const SceneFigures& s : scenes) e += s.blotch;
  return scenes.empty() ? NAN : e / double(scenes.size());
}

TuneCsv::~TuneCsv() {
  if (file_) std::fclose(file_);
}

Status TuneCsv::open(const std::string& path, const std::vector<std::string>& scenes, std::uint32_t objectiveRays) {
  path_ = path;
  scenes_ = scenes;
  objectiveRays_ = objectiveRays;
  rows_.clear();
  index_.clear();
  session_ = 1;
  withoutSession_ = false;
  linesWithoutSession_.clear();
  header_ = header(scenes, objectiveRays);
  const std::string& expected = header_;
  std::ifstream in(path);
  bool exists = false;
  if (in) {
    std::string line;
    if (std::getline(in, line)) {
      exists = true;
      withoutSession_ = line == headerWithoutSession(scenes, objectiveRays);
      if (line != expected && !withoutSession_)
        return Status::error(StatusCode::InvalidInput,
                             path + " was written by another tune (its header differs: another scene set, another "
                                    "objective or an older format); give another --out or delete it. Expected header:\n  " + expected +
                                 "\nfound:\n  " + line);
      const std::size_t columns = split(withoutSession_ ? headerWithoutSession(scenes, objectiveRays) : expected).size();
      for (int lineNo = 2; std::getline(in, line); ++lineNo) {
        if (line.empty()) continue;
        const std::vector<std::string> f = split(line);
        auto bad = [&](const std::string& why) {
          return Status::error(StatusCode::IoError, path + ":" + std::to_string(lineNo) + ": " + why +
                                                        " (an interrupted write? delete that line to resume)");
        };
        if (f.size() != columns) return bad("expected " + std::to_string(columns) + " fields, got " + std::to_string(f.size()));
        TuneRow r;
        std::size_t i = 0;
        r.kind = f[i++], r.name = f[i++], r.backend = f[i++], r.depth = f[i++], r.inputs = f[i++];
        const std::string size = f[i++];
        unsigned w = 0, h = 0;
        char tail = 0;
        if (std::sscanf(size.c_str(), "%ux%u%c", &w, &h, &tail) != 2) return bad("bad size '" + size + "'");
        r.size = {w, h};
        if (!parseWhole(f[i++], r.convergedTaps)) return bad("bad converged_taps");
        if (!parseWhole(f[i++], r.ownConvergedFrames)) return bad("bad own_converged_frames");
        if (objectiveRays && (!parseWhole(f[i++], r.objectiveRays) || r.objectiveRays == 0)) return bad("bad a_rays");
        for (const std::string& s : kTunedSettings)
          if (!setTunedSetting(r.settings, s, f[i++])) return bad("bad " + s + " '" + f[i - 1] + "'");
        if (!parseWhole(f[i++], r.runs)) return bad("bad runs");
        for (std::size_t s = 0; s < scenes.size(); ++s) {
          SceneFigures g;
          double* fields[] = {&g.ms, &g.rmse, &g.blotch, &g.highFrequency, &g.silhouette};
          for (double* v : fields)
            if (!parseNumber(f[i++], *v)) return bad("bad number '" + f[i - 1] + "'");
          r.scenes.push_back(g);
        }
        r.session = 1;
        if (withoutSession_) linesWithoutSession_.push_back(line);
        else if (!parseWhole(f[i++], r.session) || r.session == 0 || r.session == UINT32_MAX) return bad("bad session");
        session_ = std::max(session_, r.session + 1);
        index_[r.key()] = rows_.size();
        rows_.push_back(std::move(r));
      }
    }
  }
  in.close();
  file_ = std::fopen(path.c_str(), "a");
  if (!file_) return Status::error(StatusCode::IoError, "cannot open " + path + " for appending: " + std::strerror(errno));
  if (!exists && (std::fprintf(file_, "%s\n", expected.c_str()) < 0 || std::fflush(file_) != 0))
    return Status::error(StatusCode::IoError, "cannot write " + path);
  return Status::success();
}

const TuneRow* TuneCsv::find(const std::string& key) const {
  const auto it = index_.find(key);
  return it == index_.end() ? nullptr : &rows_[it->second];
}

Status TuneCsv::addSessionColumn() {
  // Rewritten whole under a new name and renamed over the file, so that it is never half old-format.
  std::string text = header_ + "\n";
  for (const std::string& line : linesWithoutSession_) text += line + ",1\n";
  std::fclose(file_);
  file_ = nullptr;
  if (Status s = samples::writeFileInPlace(path_, text); !s) return s;
  file_ = std::fopen(path_.c_str(), "a");
  if (!file_) return Status::error(StatusCode::IoError, "cannot open " + path_ + " for appending: " + std::strerror(errno));
  withoutSession_ = false;
  linesWithoutSession_.clear();
  return Status::success();
}

Status TuneCsv::append(const TuneRow& row) {
  if (withoutSession_)
    if (Status s = addSessionColumn(); !s) return s;
  std::string line = row.columns() + "," + std::to_string(row.runs);
  for (const SceneFigures& g : row.scenes)
    for (double v : {g.ms, g.rmse, g.blotch, g.highFrequency, g.silhouette}) line += "," + number(v);
  line += "," + std::to_string(session_);
  if (std::fprintf(file_, "%s\n", line.c_str()) < 0 || std::fflush(file_) != 0)
    return Status::error(StatusCode::IoError, "cannot append to " + path_);
  // Keep what was written, as a rerun would read it back (the selection uses the rounded values).
  std::vector<std::string> f = split(line);
  TuneRow r = row;
  r.session = session_;
  std::size_t i = f.size() - 1 - row.scenes.size() * 5;
  for (SceneFigures& g : r.scenes)
    for (double* v : {&g.ms, &g.rmse, &g.blotch, &g.highFrequency, &g.silhouette}) parseNumber(f[i++], *v);
  index_[r.key()] = rows_.size();
  rows_.push_back(std::move(r));
  return Status::success();
}

}  // namespace sao::bench
