// glTF cameras: their values checked in the JSON, then the default scene's camera nodes as views.
#include "gltf_cameras.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <string>

#include "file_checks.h"

namespace sao::scenes::detail {

namespace {

using nlohmann::json;

// The shortest text that reads back as v ("0.1", not "0.10000000000000001").
std::string number(double v) {
  char text[32];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, v);
  return ec == std::errc() ? std::string(text, end) : "?";
}

class CameraChecker {
 public:
  CameraChecker(std::string_view name, std::size_t index)
      : name_(name), at_("cameras[" + std::to_string(index) + "]") {}

  Status error(const std::string& problem) const { return fileError(StatusCode::IoError, name_, "glTF: " + problem); }

  Status check(const json& camera) const {
    const auto type = camera.find("type");
    if (type == camera.end()) return error(at_ + " has no type (\"perspective\" or \"orthographic\")");
    const std::string kind = type->get<std::string>();  // a string: checkGltfTypes
    if (kind != "perspective" && kind != "orthographic") {
      std::string shown = type->dump();
      if (shown.size() > 40) shown = shown.substr(0, 40) + "...";
      return error(at_ + ".type is " + shown + "; it must be \"perspective\" or \"orthographic\"");
    }
    const auto values = camera.find(kind);
    if (values == camera.end()) return error(at_ + " is of type \"" + kind + "\" but has no \"" + kind + "\" object");
    const std::string at = at_ + "." + kind;
    double v[4];  // perspective: yfov, znear, zfar, aspectRatio; orthographic: xmag, ymag, znear, zfar
    bool given[4];
    const char* const perspective[] = {"yfov", "znear", "zfar", "aspectRatio"};
    const char* const orthographic[] = {"xmag", "ymag", "znear", "zfar"};
    const char* const* keys = kind == "perspective" ? perspective : orthographic;
    const int required = kind == "perspective" ? 2 : 4;
    for (int k = 0; k < 4; ++k) {
      const auto it = values->find(keys[k]);
      given[k] = it != values->end();
      if (!given[k] && k < required) return error(at + " has no " + keys[k] + " (a required member)");
      v[k] = given[k] ? it->get<double>() : 0.0;  // numbers: checkGltfTypes
    }
    auto bad = [&](int k, const std::string& wanted) {
      return error(at + "." + keys[k] + " is " + number(v[k]) + "; it must be " + wanted);
    };
    if (kind == "perspective") {
      if (!(v[0] > 0 && v[0] < std::numbers::pi)) return bad(0, "in (0, pi) radians");
      if (!(v[1] > 0 && std::isfinite(v[1]))) return bad(1, "above 0");
      if (given[2] && !(v[2] > v[1] && std::isfinite(v[2]))) return bad(2, "beyond znear (" + number(v[1]) + ")");
      if (given[3] && !(v[3] > 0 && std::isfinite(v[3]))) return bad(3, "above 0");
    } else {
      for (int k : {0, 1})
        if (!(v[k] > 0 && std::isfinite(v[k]))) return bad(k, "above 0");
      if (!std::isfinite(2 * v[1])) return bad(1, "at most half the largest double (the view is 2 ymag tall)");
      if (!(v[2] >= 0 && std::isfinite(v[2]))) return bad(2, "0 or more");
      if (!(v[3] > v[2] && std::isfinite(v[3]))) return bad(3, "beyond znear (" + number(v[2]) + ")");
    }
    return Status::success();
  }

 private:
  std::string_view name_;
  std::string at_;
};

bool finite(glm::dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// v at unit length, scaled first so that its squared length cannot overflow; 0 for a zero vector.
glm::dvec3 unit(glm::dvec3 v) {
  const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  return m > 0 ? glm::normalize(v / m) : glm::dvec3(0.0);
}

// The name shown for a view: one line of text.
std::string printable(std::string name) {
  for (char& c : name)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  return name;
}

}  // namespace

Status checkGltfCameras(const json& doc, std::string_view name) {
  const auto cameras = doc.find("cameras");
  if (cameras == doc.end()) return Status::success();
  for (std::size_t c = 0; c < cameras->size(); ++c)
    if (Status s = CameraChecker(name, c).check((*cameras)[c]); !s) return s;
  return Status::success();
}

Status gltfCameraViews(const tinygltf::Model& model, const std::vector<GltfCameraNode>& nodes, const Mesh& mesh,
                       std::string_view name, std::vector<View>& out) {
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi = -lo;
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  const glm::dvec3 centre = (lo + hi) * 0.5;
  const double halfDiagonal = glm::length(hi - lo) * 0.5;

  std::vector<View> views;
  std::set<std::string> taken = {"default"};
  for (const GltfCameraNode& n : nodes) {
    const tinygltf::Camera& camera = model.cameras[std::size_t(n.camera)];
    auto refuse = [&](const std::string& problem) {
      return fileError(StatusCode::IoError, name,
                       "glTF: nodes[" + std::to_string(n.node) + "] (camera " + std::to_string(n.camera) +
                           "): its world matrix " + problem);
    };
    const char* const overflow = "is not finite (the node transforms overflow)";
    // The camera looks down its local -z, +y up (glTF 2.0 section 3.10.1).
    const glm::dvec3 eye(n.world * glm::dvec4(0, 0, 0, 1));
    const glm::dvec3 forward = unit(glm::dvec3(n.world * glm::dvec4(0, 0, -1, 0)));
    const glm::dvec3 up = unit(glm::dvec3(n.world * glm::dvec4(0, 1, 0, 0)));
    if (!finite(eye) || !finite(forward) || !finite(up)) return refuse(overflow);
    if (!(glm::length(glm::cross(forward, up)) >= 1e-6))
      return refuse("leaves the camera no view direction (a zero scale, or -z and +y made parallel)");
    View v;
    v.eye = eye;
    v.up = up;
    // The target only sets the orbit distance (sao-viewer) and the framing of a switch between
    // perspective and orthographic: the depth of the scene's centre suits both. At least a
    // millionth of the eye's coordinates, so that eye and target stay apart in double.
    double distance = glm::dot(centre - eye, forward);
    if (!(distance > 0)) distance = halfDiagonal;
    distance = std::max(distance, 1e-6 * std::max({std::abs(eye.x), std::abs(eye.y), std::abs(eye.z), 1.0}));
    v.target = eye + forward * distance;
    if (!finite(v.target)) return refuse(overflow);  // an eye within a millionth of the largest double
    if (camera.type == "perspective") {
      v.fovyRadians = camera.perspective.yfov;
      v.nearDistance = camera.perspective.znear;
    } else {
      v.orthoHeight = 2.0 * camera.orthographic.ymag;  // ymag is half the height
      v.nearDistance = camera.orthographic.znear;
      v.orthoFar = camera.orthographic.zfar;
    }
    const std::string& own = !camera.name.empty() ? camera.name : model.nodes[std::size_t(n.node)].name;
    const std::string base = printable(own.empty() ? "camera " + std::to_string(n.camera) : own);
    v.name = base;
    for (int k = 2; taken.count(v.name) != 0; ++k) v.name = base + " (" + std::to_string(k) + ")";
    taken.insert(v.name);
    views.push_back(std::move(v));
  }
  out = std::move(views);
  return Status::success();
}

}  // namespace sao::scenes::detail
