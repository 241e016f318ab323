// The .scene format (docs/scene-format.md): a tokenizer, one parser per keyword, and the loader
// that reads the meshes and puts them into world space.
#include "sao/scenes/scene_file.h"

#include <algorithm>
#include <charconv>
#include <initializer_list>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "file_checks.h"
#include "sao/scenes/default_view.h"
#include "sao/scenes/mesh_file.h"

namespace sao::scenes {

namespace {

namespace fs = std::filesystem;

// Where a problem is: "PATH:LINE: PROBLEM".
struct Where {
  const std::string& path;
  int line;
  Status error(const std::string& problem) const {
    return Status::error(StatusCode::InvalidInput, path + ":" + std::to_string(line) + ": " + problem);
  }
};

// Whitespace-separated words or "double-quoted strings"; a word starting with # ends the line.
Status tokenize(std::string_view line, const Where& where, std::vector<std::string>& tokens) {
  std::size_t i = 0;
  auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; };
  while (i < line.size()) {
    if (space(line[i])) {
      ++i;
      continue;
    }
    if (line[i] == '#') break;
    if (line[i] == '"') {
      const std::size_t close = line.find('"', i + 1);
      if (close == std::string_view::npos) return where.error("unterminated quoted string");
      if (close + 1 < line.size() && !space(line[close + 1]))
        return where.error("text right after a closing quote");
      tokens.emplace_back(line.substr(i + 1, close - i - 1));
      i = close + 1;
      continue;
    }
    const std::size_t start = i;
    while (i < line.size() && !space(line[i])) ++i;
    tokens.emplace_back(line.substr(start, i - start));
  }
  return Status::success();
}

// A word of the file for a message, in quotes: printable ASCII (others as '?'), at most 40
// characters.
std::string shown(std::string_view word) {
  std::string s = "'";
  for (char c : word.substr(0, 40)) s += (c >= 32 && c < 127) ? c : '?';
  return s + (word.size() > 40 ? "...'" : "'");
}

Status parseNumber(const std::string& token, const Where& where, double& out) {
  double value = 0;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ec == std::errc::result_out_of_range) return where.error("number " + shown(token) + " is out of range");
  if (ec != std::errc() || ptr != end) return where.error(shown(token) + " is not a number");
  if (!std::isfinite(value)) return where.error(shown(token) + " is not a finite number");
  out = value;
  return Status::success();
}

// The words that start a transform operation or a view property.
bool isKeyword(std::string_view t) {
  for (std::string_view k : {"scale", "rotate-y", "translate", "matrix", "eye", "target", "fovy", "near", "ortho"})
    if (t == k) return true;
  return false;
}

// Whether a word is meant as a number (and so is an argument, not the next keyword): it starts
// with a digit, a point or a sign, or is nan / inf.
bool looksNumeric(std::string_view t) {
  if (!t.empty() && (t[0] == '+' || t[0] == '-')) t.remove_prefix(1);
  if (t.empty()) return false;
  if ((t[0] >= '0' && t[0] <= '9') || t[0] == '.') return true;
  auto lower = [](char c) { return char(c >= 'A' && c <= 'Z' ? c + 32 : c); };
  const std::string head{lower(t[0]), t.size() > 1 ? lower(t[1]) : ' ', t.size() > 2 ? lower(t[2]) : ' '};
  return head == "nan" || head == "inf";
}

// The numbers after the keyword tokens[key]: as many as look numeric, which must be one of
// `counts` (in increasing order); `what` says so in the message ("3 numbers", "1 or 3 numbers").
Status numbersAfter(const std::vector<std::string>& tokens, std::size_t key, std::initializer_list<std::size_t> counts,
                    const char* what, const Where& where, double* out, std::size_t& given) {
  given = 0;
  while (key + 1 + given < tokens.size() && looksNumeric(tokens[key + 1 + given])) ++given;
  if (std::find(counts.begin(), counts.end(), given) == counts.end()) {
    const std::size_t next = key + 1 + given;
    // A word where a number should be ("translate 1 x 2") is named; otherwise the count is wrong.
    if (given < *(counts.end() - 1) && next + 1 < tokens.size() && !isKeyword(tokens[next]) &&
        looksNumeric(tokens[next + 1]))
      return where.error(shown(tokens[next]) + " is not a number");
    return where.error(tokens[key] + " takes " + what + ", got " + std::to_string(given));
  }
  for (std::size_t k = 0; k < given; ++k)
    if (Status s = parseNumber(tokens[key + 1 + k], where, out[k]); !s) return s;
  return Status::success();
}

std::string formatNumber(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

// transform OP ARGS [OP ARGS ...]: each operation applies to the result of the previous ones.
Status parseTransform(const std::vector<std::string>& tokens, const Where& where, glm::dmat4& transform) {
  if (tokens.size() < 2) return where.error("transform needs at least one of scale, rotate-y, translate, matrix");
  glm::dmat4 m = transform;
  std::size_t i = 1;
  while (i < tokens.size()) {
    const std::string& op = tokens[i];
    if (!isKeyword(op) || op == "eye" || op == "target" || op == "fovy" || op == "near" || op == "ortho")
      return where.error("unknown transform " + shown(op) + " (expected scale, rotate-y, translate or matrix)");
    double a[16] = {};
    std::size_t n = 0;
    glm::dmat4 step(1.0);
    if (op == "scale") {
      if (Status s = numbersAfter(tokens, i, {1, 3}, "1 or 3 numbers", where, a, n); !s) return s;
      const glm::dvec3 f = n == 1 ? glm::dvec3(a[0]) : glm::dvec3(a[0], a[1], a[2]);
      if (f.x == 0 || f.y == 0 || f.z == 0) return where.error("scale 0 would flatten the mesh");
      step = glm::scale(glm::dmat4(1.0), f);
    } else if (op == "rotate-y") {
      if (Status s = numbersAfter(tokens, i, {1}, "1 number (degrees)", where, a, n); !s) return s;
      step = glm::rotate(glm::dmat4(1.0), a[0] * std::numbers::pi / 180.0, glm::dvec3(0, 1, 0));
    } else if (op == "translate") {
      if (Status s = numbersAfter(tokens, i, {3}, "3 numbers", where, a, n); !s) return s;
      step = glm::translate(glm::dmat4(1.0), glm::dvec3(a[0], a[1], a[2]));
    } else {  // matrix: 16 numbers, row by row
      if (Status s = numbersAfter(tokens, i, {16}, "16 numbers (4 rows of 4)", where, a, n); !s) return s;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) step[c][r] = a[r * 4 + c];
      if (a[12] != 0 || a[13] != 0 || a[14] != 0 || a[15] != 1)
        return where.error("matrix: the last row must be 0 0 0 1 (an affine transform)");
      const double det = glm::determinant(glm::dmat3(step));
      if (!(std::abs(det) > 0) || !std::isfinite(det)) return where.error("matrix: singular (determinant " + formatNumber(det) + ")");
    }
    m = step * m;
    i += n + 1;
  }
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return where.error("the transform overflows (a non-finite matrix)");
  transform = m;
  return Status::success();
}

// view NAME eye X Y Z target X Y Z [fovy DEG | ortho HEIGHT] [near M]
Status parseView(const std::vector<std::string>& tokens, const Where& where, SceneFileView& out) {
  if (tokens.size() < 2) return where.error("view needs a name");
  SceneFileView v;
  v.view.name = tokens[1];
  v.view.up = {0, 1, 0};
  v.view.fovyRadians = std::numbers::pi / 3;
  v.line = where.line;
  bool haveEye = false, haveTarget = false, haveFovy = false, haveOrtho = false;
  std::size_t i = 2;
  while (i < tokens.size()) {
    const std::string& key = tokens[i];
    const bool triple = key == "eye" || key == "target";
    if (!triple && key != "fovy" && key != "near" && key != "ortho")
      return where.error("unknown view property " + shown(key) + " (expected eye, target, fovy, ortho, near)");
    const bool repeated = key == "eye"      ? haveEye
                          : key == "target" ? haveTarget
                          : key == "fovy"   ? haveFovy
                          : key == "ortho"  ? haveOrtho
                                            : v.nearDistance.has_value();
    if (repeated) return where.error("view property '" + key + "' given twice");
    double a[3] = {};
    std::size_t n = 0;
    if (Status s = numbersAfter(tokens, i, {triple ? 3u : 1u}, triple ? "3 numbers" : "1 number", where, a, n); !s)
      return s;
    if (key == "eye") v.view.eye = {a[0], a[1], a[2]}, haveEye = true;
    else if (key == "target") v.view.target = {a[0], a[1], a[2]}, haveTarget = true;
    else if (key == "fovy") {
      if (!(a[0] > 0 && a[0] < 180)) return where.error("fovy " + formatNumber(a[0]) + " is outside (0, 180) degrees");
      v.view.fovyRadians = a[0] * std::numbers::pi / 180.0;
      haveFovy = true;
    } else if (key == "ortho") {
      // The full height of the view in scene units; the width follows the image's aspect.
      if (!(a[0] > 0)) return where.error("ortho " + formatNumber(a[0]) + ": the view height must be greater than 0");
      v.view.orthoHeight = a[0];
      haveOrtho = true;
    } else {
      if (!(a[0] > 0)) return where.error("near " + formatNumber(a[0]) + " must be greater than 0");
      v.nearDistance = a[0];
    }
    i += n + 1;
  }
  if (haveFovy && haveOrtho)
    return where.error("view " + shown(v.view.name) + " has both fovy and ortho (a perspective or an orthographic view: pick one)");
  if (!haveEye) return where.error("view " + shown(v.view.name) + " has no eye");
  if (!haveTarget) return where.error("view " + shown(v.view.name) + " has no target");
  const glm::dvec3 d = v.view.target - v.view.eye;
  const double length = glm::length(d);
  if (!(length > 0)) return where.error("view " + shown(v.view.name) + ": eye and target are the same point");
  if (!std::isfinite(length)) return where.error("view " + shown(v.view.name) + ": eye and target are too far apart");
  if (glm::length(glm::cross(d / length, v.view.up)) < 1e-6)
    return where.error("view " + shown(v.view.name) + " looks straight up or down (up is +y): move the target sideways a little");
  out = std::move(v);
  return Status::success();
}

// Applies `transform` to `mesh` and appends it; the result must stay within float range.
Status appendTransformed(Mesh& scene, const Mesh& mesh, const glm::dmat4& transform, const Where& where,
                         const std::string& meshPath) {
  const std::size_t base = scene.positions.size();
  if (base + mesh.positions.size() > std::numeric_limits<std::uint32_t>::max())
    return where.error("the meshes have more than 2^32 - 1 vertices in all");
  std::vector<glm::vec3> positions;
  positions.reserve(mesh.positions.size());
  constexpr double kMax = std::numeric_limits<float>::max();
  for (std::size_t k = 0; k < mesh.positions.size(); ++k) {
    const glm::dvec3 q = glm::dvec3(transform * glm::dvec4(glm::dvec3(mesh.positions[k]), 1.0));
    if (!(std::abs(q.x) <= kMax && std::abs(q.y) <= kMax && std::abs(q.z) <= kMax))
      return where.error("the transform takes vertex " + std::to_string(k) + " of " + meshPath +
                         " beyond the range of a float");
    positions.emplace_back(q);
  }
  scene.positions.insert(scene.positions.end(), positions.begin(), positions.end());
  scene.indices.reserve(scene.indices.size() + mesh.indices.size());
  for (std::uint32_t i : mesh.indices) scene.indices.push_back(static_cast<std::uint32_t>(base) + i);
  return Status::success();
}

}  // namespace

Status parseSceneFile(std::string_view text, const std::string& path, SceneFile& out) {
  SceneFile file;
  const fs::path folder = fs::path(path).parent_path();
  // A UTF-8 byte-order mark (Windows editors write one) is skipped.
  std::size_t start = text.starts_with(detail::kUtf8ByteOrderMark) ? detail::kUtf8ByteOrderMark.size() : 0;
  int lineNumber = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(start, end - start);
    start = end + 1;
    const Where where{path, ++lineNumber};
    if (line.find('\0') != std::string_view::npos) return where.error("contains a NUL byte");
    std::vector<std::string> tokens;
    if (Status s = tokenize(line, where, tokens); !s) return s;
    if (tokens.empty()) continue;
    const std::string& keyword = tokens[0];
    if (keyword == "mesh") {
      if (tokens.size() != 2) return where.error("mesh takes one path (quote a path with spaces), got " + std::to_string(tokens.size() - 1) + " words");
      if (tokens[1].empty()) return where.error("mesh: empty path");
      if (!isMeshFileExtension(tokens[1]))
        return where.error(shown(tokens[1]) + " is not a mesh file (.gltf, .glb, .obj, .ply)");
      const fs::path meshPath(tokens[1]);
      file.meshes.push_back({(meshPath.is_absolute() ? meshPath : folder / meshPath).string(), glm::dmat4(1.0), where.line});
    } else if (keyword == "transform") {
      if (file.meshes.empty()) return where.error("transform before any mesh line (it applies to the mesh above it)");
      if (Status s = parseTransform(tokens, where, file.meshes.back().transform); !s) return s;
    } else if (keyword == "units") {
      if (tokens.size() != 2) return where.error("units takes one word (" + std::string(kLengthUnitNames) + ")");
      const auto unit = parseLengthUnit(tokens[1]);
      if (!unit)
        return where.error("unknown unit " + shown(tokens[1]) + " (expected " + std::string(kLengthUnitNames) + ")");
      if (file.units) return where.error("units given twice (first on " + file.units->source + ")");
      file.units = DeclaredUnits{*unit, path + ":" + std::to_string(where.line)};
    } else if (keyword == "view") {
      SceneFileView view;
      if (Status s = parseView(tokens, where, view); !s) return s;
      for (const SceneFileView& other : file.views)
        if (other.view.name == view.view.name)
          return where.error("view " + shown(view.view.name) + " is defined twice (first on line " + std::to_string(other.line) + ")");
      file.views.push_back(std::move(view));
    } else {
      return where.error("unknown keyword " + shown(keyword) + " (expected mesh, transform, view or units)");
    }
    if (end == text.size()) break;
  }
  if (file.meshes.empty()) return detail::fileError(StatusCode::InvalidInput, path, "has no mesh line");
  out = std::move(file);
  return Status::success();
}

Status loadSceneFile(const std::string& path, Scene& out) {
  std::string text;
  if (Status s = detail::readWholeFile(path, kMaxSceneFileBytes, text); !s) return s;
  SceneFile file;
  if (Status s = parseSceneFile(text, path, file); !s) return s;
  Scene scene;
  scene.name = fs::path(path).filename().string();
  for (const SceneFileMesh& m : file.meshes) {
    const Where where{path, m.line};
    Mesh mesh;
    if (Status s = loadMeshFile(m.path, mesh); !s) return Status::error(s.code, path + ":" + std::to_string(m.line) + ": " + s.message);
    removeDegenerateTriangles(mesh, path + ":" + std::to_string(m.line) + ": " + m.path, scene.warnings);
    if (scene.mesh.triangleCount() + mesh.triangleCount() > kMaxMeshTriangles)
      return where.error("the meshes have more than " + std::to_string(kMaxMeshTriangles) + " triangles in all");
    if (Status s = appendTransformed(scene.mesh, mesh, m.transform, where, m.path); !s) return s;
  }
  if (Status s = validateMesh(scene.mesh, path); !s) return s;
  const double near = defaultNearDistance(scene.mesh);
  for (const SceneFileView& v : file.views) {
    scene.views.push_back(v.view);
    scene.views.back().nearDistance = v.nearDistance.value_or(near);
    if (scene.views.back().orthographic()) fitOrthoFar(scene.views.back(), scene.mesh);
  }
  if (scene.views.empty()) scene.views.push_back(defaultView(scene.mesh));
  scene.units = file.units;
  const bool allGltf = std::all_of(file.meshes.begin(), file.meshes.end(), [](const SceneFileMesh& m) {
    const std::string ext = detail::lowerExtension(m.path);
    return ext == ".gltf" || ext == ".glb";
  });
  if (!scene.units && allGltf)
    scene.units = DeclaredUnits{LengthUnit::Metre, "glTF meshes: metres by their specification"};
  out = std::move(scene);
  return Status::success();
}

}  // namespace sao::scenes
