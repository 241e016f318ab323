// glTF cameras as views (src/gltf_cameras.h, docs/scene-format.md "glTF cameras"): the committed
// tests/scenes/data/cameras.gltf (a perspective camera on a rotated, translated and scaled node, an
// orthographic one under a translated parent looking straight down, an unnamed one, one camera on
// two nodes, an unused one), checked to 1e-12 against the transforms worked out by hand; names,
// order, files without cameras, real models, and every refusal with its message.
#include <cmath>
#include <memory>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sao/raytrace/raytrace.h"
#include "sao/scenes/default_view.h"
#include "sao/scenes/mesh_file.h"
#include "sao/scenes/scene.h"
#include "test_models.h"

namespace sao::scenes {
namespace {

using test::kAssimpModels;
using test::TempDir;

const std::string kCamerasGltf = SAO_SCENES_TEST_DATA "/cameras.gltf";
constexpr double kTol = 1e-12;

std::span<const std::uint8_t> bytes(std::string_view text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

void expectNear(glm::dvec3 got, glm::dvec3 want, const char* what) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], kTol) << what << "[" << k << "]";
}

// A view's eye, unit view direction, up, and its target's distance along that direction.
void expectPlacement(const View& v, glm::dvec3 eye, glm::dvec3 forward, glm::dvec3 up, double distance) {
  SCOPED_TRACE(v.name);
  expectNear(v.eye, eye, "eye");
  expectNear(glm::normalize(v.target - v.eye), forward, "direction");
  expectNear(v.up, up, "up");
  EXPECT_NEAR(glm::length(v.target - v.eye), distance, kTol);
}

// The share of a w x h ray-cast image of the view that hits the mesh.
double coverage(const Mesh& mesh, const View& view, std::uint32_t w, std::uint32_t h) {
  std::unique_ptr<raytrace::RayScene> rays;
  EXPECT_TRUE(raytrace::RayScene::create(mesh, rays));
  const Camera camera = makeCamera(view, w, h, INFINITY, ClipDepth::ZeroToOne, true);
  raytrace::Primary primary;
  EXPECT_TRUE(raytrace::castPrimary(*rays, view, camera, DepthFormat::D32F, primary));
  std::size_t hits = 0;
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x) hits += primary.position.at(x, y, 3) != 0.0f;
  return double(hits) / (w * h);
}

// data/cameras.gltf: the mesh spans (-2, 0, -2) to (2, 1, 2), centre (0, 0.5, 0).
TEST(GltfCameras, BecomeViewsAfterTheDefaultViewInNodeOrder) {
  Scene scene;
  const Status s = loadScene(kCamerasGltf, scene);
  ASSERT_TRUE(s) << s.message;
  ASSERT_EQ(scene.views.size(), 5u);
  // Node order (1, 3, 4, 5), not the order of the scene's walk (5, 3, 1, 4); camera 3 is on no node.
  const std::vector<std::string> names = {"default", "front", "top", "camera 2", "front (2)"};
  for (std::size_t i = 0; i < names.size(); ++i) EXPECT_EQ(scene.views[i].name, names[i]);
  const View def = defaultView(scene.mesh);
  EXPECT_EQ(scene.views[0].eye, def.eye);
  EXPECT_EQ(scene.views[0].target, def.target);
  const glm::dvec3 centre(0, 0.5, 0);

  // Node 1: translation (2, 1.5, 5), rotation Ry(30 deg) Rx(-20 deg), scale (3, 2, 0.5) (which
  // moves no direction once normalised). Rx(a) Ry(b) take -z to (-sin b cos a, sin a, -cos b cos a)
  // and +y to (sin b sin a, cos a, cos b sin a).
  const double a = -20 * std::numbers::pi / 180, b = 30 * std::numbers::pi / 180;
  const glm::dvec3 eye1(2, 1.5, 5);
  const glm::dvec3 f1(-std::sin(b) * std::cos(a), std::sin(a), -std::cos(b) * std::cos(a));
  const glm::dvec3 u1(std::sin(b) * std::sin(a), std::cos(a), std::cos(b) * std::sin(a));
  const View& front = scene.views[1];
  expectPlacement(front, eye1, f1, u1, glm::dot(centre - eye1, f1));
  EXPECT_FALSE(front.orthographic());
  EXPECT_EQ(front.fovyRadians, 0.8);
  EXPECT_EQ(front.nearDistance, 0.05);
  EXPECT_EQ(front.orthoFar, 0.0);  // zfar 100 is not used: the programs' far plane is infinite

  // Node 3 under node 2: (0, 10, 0) + (0.5, 0, 0.25), rotation Rx(-90 deg): looking straight
  // down, +y turned to -z. ymag 3 is half the height; xmag 4 is not used.
  const View& top = scene.views[2];
  expectPlacement(top, {0.5, 10, 0.25}, {0, -1, 0}, {0, 0, -1}, 9.5);
  EXPECT_TRUE(top.orthographic());
  EXPECT_EQ(top.orthoHeight, 6.0);
  EXPECT_EQ(top.nearDistance, 0.5);
  EXPECT_EQ(top.orthoFar, 20.0);

  // Node 4: no name, camera 2 has none either; no zfar.
  expectPlacement(scene.views[3], {-3, 2, 4}, {0, 0, -1}, {0, 1, 0}, 4.0);
  EXPECT_EQ(scene.views[3].fovyRadians, 1.2);
  EXPECT_EQ(scene.views[3].nearDistance, 0.1);
  // Node 5 holds camera 0 again (the camera's name wins over the node's "second front").
  expectPlacement(scene.views[4], {0, 1, 6}, {0, 0, -1}, {0, 1, 0}, 6.0);
  EXPECT_EQ(scene.views[4].fovyRadians, 0.8);

  // The cameras the programs make: the orthographic one with the file's far plane.
  const Camera ortho = makeCamera(top, 64, 36, INFINITY, ClipDepth::ZeroToOne, true);
  ASSERT_EQ(ortho.kind, ProjectionKind::Orthographic);
  DepthModel model;
  ASSERT_TRUE(analyze(ortho, model));
  EXPECT_NEAR(model.nearDistance, 0.5, 1e-12);
  EXPECT_NEAR(model.farDistance, 20.0, 1e-9);
  EXPECT_EQ(makeCamera(front, 64, 36, INFINITY, ClipDepth::ZeroToOne, true).kind, ProjectionKind::Perspective);
  // And what they see: from above, the 4 x 4 floor in a 6 x 10.67 view: 25 % of the image.
  EXPECT_NEAR(coverage(scene.mesh, top, 64, 36), 16.0 / (6.0 * 6.0 * 64 / 36), 0.03);
  EXPECT_GT(coverage(scene.mesh, front, 64, 36), 0.1);
}

TEST(GltfCameras, LoadMeshFileGivesTheCameraViewsOnly) {
  TempDir dir;
  Mesh mesh;
  std::vector<View> views = {View{}};
  Status s = loadMeshFile(kCamerasGltf, mesh, &views);
  ASSERT_TRUE(s) << s.message;
  ASSERT_EQ(views.size(), 4u);
  EXPECT_EQ(views[0].name, "front");
  EXPECT_EQ(views[1].orthoHeight, 6.0);
  // From memory the same; an OBJ has none.
  const std::vector<char> file = sao::test::readBytes(kCamerasGltf);
  const std::string text(file.begin(), file.end());
  std::vector<View> fromMemory;
  ASSERT_TRUE(loadMeshFromMemory(bytes(text), "gltf", "mem", mesh, &fromMemory));
  ASSERT_EQ(fromMemory.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(fromMemory[i].name, views[i].name);
    EXPECT_EQ(fromMemory[i].eye, views[i].eye);
    EXPECT_EQ(fromMemory[i].target, views[i].target);
  }
  ASSERT_TRUE(loadMeshFile(dir.write("cube.obj", test::kCubeObj), mesh, &views));
  EXPECT_TRUE(views.empty());
}

// The mesh of data/cameras.gltf in node 0, then `nodes`; the scene's roots `roots`; `cameras` as
// given (none when empty).
std::string gltfWith(const std::string& nodes, const std::string& roots, const std::string& cameras) {
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": )" + roots + R"(}],
  "nodes": [{"mesh": 0})" + (nodes.empty() ? "" : ", " + nodes) + "],\n" +
         (cameras.empty() ? "" : R"("cameras": [)" + cameras + "],\n") +
         R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "buffers": [{"byteLength": 144, "uri": "data:application/octet-stream;base64,AAAAwAAAAAAAAADAAAAAQAAAAAAAAADAAAAAQAAAAAAAAABAAAAAwAAAAAAAAABAAAAAvwAAAAAAAAC/AAAAPwAAAAAAAAC/AAAAPwAAAAAAAAA/AAAAvwAAAAAAAAA/AAAAAAAAgD8AAAAAAAACAAEAAAADAAIABAAIAAUABQAIAAYABgAIAAcABwAIAAQA"}],
  "bufferViews": [{"buffer": 0, "byteLength": 108}, {"buffer": 0, "byteOffset": 108, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 9, "type": "VEC3"},
                {"bufferView": 1, "componentType": 5123, "count": 18, "type": "SCALAR"}]})";
}

constexpr const char* kPerspective = R"({"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}})";

TEST(GltfCameras, WithoutCameraNodesAMeshFileHasTheDefaultViewOnly) {
  TempDir dir;
  Scene scene;
  // No cameras at all; cameras that no node holds; a camera node outside the default scene.
  for (const std::string& text :
       {gltfWith("", "[0]", ""), gltfWith("", "[0]", kPerspective), gltfWith(R"({"camera": 0})", "[0]", kPerspective)}) {
    const Status s = loadScene(dir.write("none.gltf", text), scene);
    ASSERT_TRUE(s) << s.message;
    ASSERT_EQ(scene.views.size(), 1u);
    EXPECT_EQ(scene.views[0].name, "default");
  }
  // A scene file's glTF meshes bring no views: its own view lines (or its default view) decide.
  const std::string sceneFile = dir.write("cameras.scene", "mesh \"" + kCamerasGltf + "\"\n");
  ASSERT_TRUE(loadScene(sceneFile, scene));
  ASSERT_EQ(scene.views.size(), 1u);
  EXPECT_EQ(scene.views[0].name, "default");
}

TEST(GltfCameras, NamesAreOneLineAndUnique) {
  TempDir dir;
  const std::string text = gltfWith(
      R"({"camera": 0, "translation": [0, 1, 5]}, {"camera": 0, "translation": [0, 1, 6]},
         {"name": "node\nname", "camera": 1, "translation": [0, 1, 7]}, {"camera": 2, "translation": [0, 1, 8]},
         {"camera": 1, "translation": [0, 1, 9]})",
      "[0, 1, 2, 3, 4, 5]",
      std::string(kPerspective) + R"(, {"name": "", "type": "perspective", "perspective": {"yfov": 1, "znear": 1}},
         {"name": "default", "type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0, "zfar": 9}})");
  Scene scene;
  const Status s = loadScene(dir.write("names.gltf", text), scene);
  ASSERT_TRUE(s) << s.message;
  const std::vector<std::string> names = {"default", "camera 0", "camera 0 (2)", "node name", "default (2)",
                                          "camera 1"};
  ASSERT_EQ(scene.views.size(), names.size());
  for (std::size_t i = 0; i < names.size(); ++i) EXPECT_EQ(scene.views[i].name, names[i]);
  // An orthographic znear of 0 is valid glTF and kept.
  EXPECT_EQ(scene.views[4].nearDistance, 0.0);
  EXPECT_TRUE(makeCamera(scene.views[4], 16, 16, INFINITY, ClipDepth::ZeroToOne, true).kind ==
              ProjectionKind::Orthographic);
}

struct BadCamera {
  std::string camera;    // cameras[0], held by node 1
  std::string expected;  // the message after "mem: glTF: "
};

TEST(GltfCameras, BadValuesAreRefusedNamingTheCameraAndField) {
  const std::string persp = R"({"type": "perspective", "perspective": )";
  const std::string ortho = R"({"type": "orthographic", "orthographic": )";
  const BadCamera cases[] = {
      {persp + R"({"yfov": 0, "znear": 0.1}})", "cameras[0].perspective.yfov is 0; it must be in (0, pi) radians"},
      {persp + R"({"yfov": -1, "znear": 0.1}})", "cameras[0].perspective.yfov is -1; it must be in (0, pi) radians"},
      {persp + R"({"yfov": 3.1416, "znear": 0.1}})",
       "cameras[0].perspective.yfov is 3.1416; it must be in (0, pi) radians"},
      {persp + R"({"yfov": 1, "znear": 0}})", "cameras[0].perspective.znear is 0; it must be above 0"},
      {persp + R"({"yfov": 1, "znear": -0.1}})", "cameras[0].perspective.znear is -0.1; it must be above 0"},
      {persp + R"({"yfov": 1, "znear": 0.1, "zfar": 0.1}})",
       "cameras[0].perspective.zfar is 0.1; it must be beyond znear (0.1)"},
      // An explicit 0 is not an absent zfar (tinygltf reads both as 0).
      {persp + R"({"yfov": 1, "znear": 0.1, "zfar": 0}})",
       "cameras[0].perspective.zfar is 0; it must be beyond znear (0.1)"},
      {persp + R"({"yfov": 1, "znear": 0.1, "aspectRatio": 0}})",
       "cameras[0].perspective.aspectRatio is 0; it must be above 0"},
      {persp + R"({"znear": 0.1}})", "cameras[0].perspective has no yfov (a required member)"},
      {persp + R"({"yfov": 1}})", "cameras[0].perspective has no znear (a required member)"},
      {persp + R"({"yfov": "wide", "znear": 0.1}})",
       "cameras[0].perspective.yfov is a string; glTF 2.0 requires a number"},
      {ortho + R"({"xmag": 0, "ymag": 1, "znear": 0, "zfar": 1}})",
       "cameras[0].orthographic.xmag is 0; it must be above 0"},
      {ortho + R"({"xmag": 1, "ymag": -2, "znear": 0, "zfar": 1}})",
       "cameras[0].orthographic.ymag is -2; it must be above 0"},
      {ortho + R"({"xmag": 1, "ymag": 1e308, "znear": 0, "zfar": 1}})",
       "cameras[0].orthographic.ymag is 1e+308; it must be at most half the largest double (the view is 2 ymag tall)"},
      {ortho + R"({"xmag": 1, "ymag": 1, "znear": -0.5, "zfar": 1}})",
       "cameras[0].orthographic.znear is -0.5; it must be 0 or more"},
      {ortho + R"({"xmag": 1, "ymag": 1, "znear": 1, "zfar": 1}})",
       "cameras[0].orthographic.zfar is 1; it must be beyond znear (1)"},
      {ortho + R"({"xmag": 1, "ymag": 1, "znear": 1, "zfar": 0.5}})",
       "cameras[0].orthographic.zfar is 0.5; it must be beyond znear (1)"},
      {ortho + R"({"xmag": 1, "ymag": 1, "znear": 1}})", "cameras[0].orthographic has no zfar (a required member)"},
      {R"({"perspective": {"yfov": 1, "znear": 1}})", R"(cameras[0] has no type ("perspective" or "orthographic"))"},
      {R"({"type": "fisheye"})", R"(cameras[0].type is "fisheye"; it must be "perspective" or "orthographic")"},
      {R"({"type": "perspective", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0, "zfar": 1}})",
       R"(cameras[0] is of type "perspective" but has no "perspective" object)"},
      // Cameras that no node holds are checked too (as every mesh is).
      {std::string(kPerspective) + ", " + ortho + R"({"xmag": 1, "ymag": 0, "znear": 0, "zfar": 1}})",
       "cameras[1].orthographic.ymag is 0; it must be above 0"},
  };
  for (const BadCamera& c : cases) {
    SCOPED_TRACE(c.camera);
    const std::string text = gltfWith(R"({"camera": 0, "translation": [0, 1, 5]})", "[0, 1]", c.camera);
    Mesh mesh;
    mesh.positions = {{4, 5, 6}};
    std::vector<View> views(2);
    const Status s = loadMeshFromMemory(bytes(text), "gltf", "mem", mesh, &views);
    EXPECT_EQ(s.code, StatusCode::IoError);
    EXPECT_EQ(s.message, "mem: glTF: " + c.expected);
    EXPECT_EQ(mesh.positions.size(), 1u);
    EXPECT_EQ(views.size(), 2u) << "the output changed on error";
  }
  // A number beyond a double (JSON has no infinity) is not valid JSON.
  Mesh mesh;
  const std::string huge = gltfWith(R"({"camera": 0})", "[0, 1]", persp + R"({"yfov": 1e999, "znear": 0.1}})");
  const Status s = loadMeshFromMemory(bytes(huge), "gltf", "mem", mesh);
  EXPECT_EQ(s.message, "mem: not valid JSON ([json.exception.out_of_range.406] number overflow parsing '1e999')");
  // Files name themselves.
  TempDir dir;
  Scene scene;
  const std::string path = dir.write("bad.gltf", gltfWith(R"({"camera": 0})", "[0, 1]", persp + R"({"yfov": 0, "znear": 1}})"));
  EXPECT_EQ(loadScene(path, scene).message, path + ": glTF: cameras[0].perspective.yfov is 0; it must be in (0, pi) radians");
}

TEST(GltfCameras, CameraNodesWithoutADirectionAreRefused) {
  struct Case {
    std::string nodes, roots, expected;
  };
  const Case cases[] = {
      {R"({"camera": 5})", "[0, 1]", "nodes[1].camera is 5, which does not exist"},
      {R"({"camera": 0, "scale": [1, 0, 1]})", "[0, 1]",
       "nodes[1] (camera 0): its world matrix leaves the camera no view direction (a zero scale, or -z and +y made "
       "parallel)"},
      {R"({"children": [2], "scale": [0, 0, 0]}, {"camera": 0})", "[0, 1]",
       "nodes[2] (camera 0): its world matrix leaves the camera no view direction (a zero scale, or -z and +y made "
       "parallel)"},
      // -z taken to +y.
      {R"({"camera": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, -1, 0, 0, 0, 0, 0, 1]})", "[0, 1]",
       "nodes[1] (camera 0): its world matrix leaves the camera no view direction (a zero scale, or -z and +y made "
       "parallel)"},
      {R"({"translation": [1e308, 0, 0], "children": [2]}, {"camera": 0, "translation": [1e308, 0, 0]})", "[0, 1]",
       "nodes[2] (camera 0): its world matrix is not finite (the node transforms overflow)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.nodes);
    const std::string text = gltfWith(c.nodes, c.roots, kPerspective);
    Mesh mesh;
    std::vector<View> views(2);
    const Status s = loadMeshFromMemory(bytes(text), "gltf", "mem", mesh, &views);
    EXPECT_EQ(s.code, StatusCode::IoError);
    EXPECT_EQ(s.message, "mem: glTF: " + c.expected);
    EXPECT_TRUE(mesh.positions.empty());
    EXPECT_EQ(views.size(), 2u) << "the output changed on error";
    // Without asking for the cameras, only the reference is checked (as a node's mesh is).
    EXPECT_EQ(bool(loadMeshFromMemory(bytes(text), "gltf", "mem", mesh)), c.expected.find("does not exist") == std::string::npos);
  }
}

TEST(GltfCameras, RealModelsCamerasAreTheirViews) {
  if (!std::filesystem::is_directory(kAssimpModels / "glTF2"))
    GTEST_SKIP() << kAssimpModels << " is missing: install assimp-testmodels (ci/setup.sh does)";
  // Khronos' Cameras sample: both cameras at (0.5, 0.5, 3) looking down -z at a quad.
  Scene scene;
  Status s = loadScene((kAssimpModels / "glTF2/cameras/Cameras.gltf").string(), scene);
  ASSERT_TRUE(s) << s.message;
  ASSERT_EQ(scene.views.size(), 3u);
  EXPECT_EQ(scene.views[1].name, "camera 0");
  EXPECT_EQ(scene.views[2].name, "camera 1");
  for (int i : {1, 2}) expectNear(scene.views[std::size_t(i)].eye, {0.5, 0.5, 3}, "eye");
  EXPECT_EQ(scene.views[1].fovyRadians, 0.7);
  EXPECT_EQ(scene.views[2].orthoHeight, 2.0);
  EXPECT_EQ(scene.views[2].orthoFar, 100.0);
  for (int i : {1, 2}) EXPECT_GT(coverage(scene.mesh, scene.views[std::size_t(i)], 32, 32), 0.1);
  // 2CylinderEngine: one camera, node 81, a matrix (its columns read as written, float data).
  s = loadScene((kAssimpModels / "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb").string(), scene);
  ASSERT_TRUE(s) << s.message;
  ASSERT_EQ(scene.views.size(), 2u);
  const View& v = scene.views[1];
  EXPECT_EQ(v.name, "camera 0");
  expectNear(v.eye, {1005.9874267578125, 766.3170776367188, 953.3455810546875}, "eye");
  expectNear(glm::normalize(v.target - v.eye),
             -glm::normalize(glm::dvec3(0.6246951818466187, 0.4685211479663849, 0.6246950030326843)), "direction");
  EXPECT_EQ(v.fovyRadians, 0.3143463730812073);
  EXPECT_EQ(v.nearDistance, 0.04999999701976776);
  EXPECT_GT(coverage(scene.mesh, v, 32, 32), 0.1);
}

}  // namespace
}  // namespace sao::scenes
