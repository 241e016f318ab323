// Scene files (sao/scenes/scene_file.h, docs/scene-format.md): a round trip with transforms and
// views, the committed example, and every syntax and load error with its exact message.
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sao/scenes/mesh_file.h"
#include "sao/scenes/scene.h"
#include "sao/scenes/scene_file.h"
#include "test_models.h"

namespace sao::scenes {
namespace {

using test::kCubeObj;
using test::TempDir;

constexpr double kPi = std::numbers::pi;

bool hasPosition(const Mesh& mesh, std::size_t first, std::size_t count, glm::dvec3 p) {
  for (std::size_t i = first; i < first + count; ++i)
    if (glm::length(glm::dvec3(mesh.positions[i]) - p) < 1e-5) return true;
  return false;
}

TEST(SceneFile, RoundTripWithTransformsAndTwoViews) {
  TempDir dir;
  dir.write("cube.obj", kCubeObj);
  std::filesystem::create_directories(dir.file("sub dir"));
  dir.write("sub dir/cube 2.obj", kCubeObj);
  const std::string path = dir.write("two.scene",
                                     "# two cubes\r\n"
                                     "mesh cube.obj   # relative to the scene file\r\n"
                                     "transform scale 2 rotate-y 90\n"
                                     "transform translate 1 0 0\n"
                                     "\n"
                                     "mesh \"sub dir/cube 2.obj\"\n"
                                     "  transform matrix 1 0 0 5   0 1 0 0   0 0 1 0   0 0 0 1\n"
                                     "view front eye 0 2 8 target 0 0.5 0 fovy 45 near 0.05\n"
                                     "view side target 0 0 0 eye 8 1 0\n");
  Scene scene;
  const Status s = loadScene(path, scene);
  ASSERT_TRUE(s) << s.message;
  EXPECT_EQ(scene.name, "two.scene");
  ASSERT_EQ(scene.mesh.triangleCount(), 24u);
  ASSERT_EQ(scene.mesh.positions.size(), 16u);
  EXPECT_TRUE(validateMesh(scene.mesh, path));
  // The first cube: scaled by 2, turned 90 degrees about +y (+x goes to -z), moved by +1 in x.
  EXPECT_TRUE(hasPosition(scene.mesh, 0, 8, {1, 0, 0}));    // from (0, 0, 0)
  EXPECT_TRUE(hasPosition(scene.mesh, 0, 8, {1, 0, -2}));   // from (1, 0, 0)
  EXPECT_TRUE(hasPosition(scene.mesh, 0, 8, {3, 2, 0}));    // from (0, 1, 1)
  EXPECT_TRUE(hasPosition(scene.mesh, 0, 8, {3, 2, -2}));   // from (1, 1, 1)
  // The second: the matrix, row by row, moves it by +5 in x.
  EXPECT_TRUE(hasPosition(scene.mesh, 8, 8, {5, 0, 0}));
  EXPECT_TRUE(hasPosition(scene.mesh, 8, 8, {6, 1, 1}));
  for (std::uint32_t i = 0; i < 36; ++i) EXPECT_LT(scene.mesh.indices[i], 8u);
  for (std::uint32_t i = 36; i < 72; ++i) EXPECT_GE(scene.mesh.indices[i], 8u);

  ASSERT_EQ(scene.views.size(), 2u);
  const View& front = scene.views[0];
  EXPECT_EQ(front.name, "front");
  EXPECT_EQ(front.eye, glm::dvec3(0, 2, 8));
  EXPECT_EQ(front.target, glm::dvec3(0, 0.5, 0));
  EXPECT_EQ(front.up, glm::dvec3(0, 1, 0));
  EXPECT_NEAR(front.fovyRadians, 45 * kPi / 180, 1e-15);
  EXPECT_EQ(front.nearDistance, 0.05);
  const View& side = scene.views[1];
  EXPECT_EQ(side.name, "side");
  EXPECT_EQ(side.eye, glm::dvec3(8, 1, 0));
  EXPECT_NEAR(side.fovyRadians, kPi / 3, 1e-15);
  // Bounds (1, 0, -2) - (6, 2, 1): the default near plane is a hundredth of the diagonal.
  EXPECT_NEAR(side.nearDistance, std::sqrt(25.0 + 4 + 9) / 100, 1e-9);
}

TEST(SceneFile, WithoutViewsGetsTheDefaultView) {
  TempDir dir;
  dir.write("cube.obj", kCubeObj);
  Scene scene;
  ASSERT_TRUE(loadScene(dir.write("one.scene", "mesh cube.obj\ntransform translate 10 0 0\n"), scene));
  ASSERT_EQ(scene.views.size(), 1u);
  EXPECT_EQ(scene.views[0].name, "default");
  EXPECT_NEAR(glm::length(scene.views[0].target - glm::dvec3(10.5, 0.5, 0.5)), 0.0, 1e-12);
}

TEST(SceneFile, CommittedExampleLoads) {
  Scene scene;
  const Status s = loadScene(SAO_SCENES_TEST_DATA "/boxes.scene", scene);
  ASSERT_TRUE(s) << s.message;
  EXPECT_EQ(scene.mesh.triangleCount(), 24u);
  ASSERT_EQ(scene.views.size(), 2u);
  EXPECT_EQ(scene.views[0].name, "front");
  EXPECT_EQ(scene.views[1].name, "above");
  float top = -INFINITY, bottom = INFINITY;
  for (const glm::vec3& p : scene.mesh.positions) top = std::max(top, p.y), bottom = std::min(bottom, p.y);
  EXPECT_FLOAT_EQ(top, 1.0f);
  EXPECT_FLOAT_EQ(bottom, -0.1f);
}

// An `ortho H` view: H is the full view height in scene units; the camera is orthographic with a
// finite far plane just beyond the mesh (fitOrthoFar), and a perspective view of the same file
// stays perspective.
TEST(SceneFile, OrthographicViewParsesAndMakesAnOrthographicCamera) {
  TempDir dir;
  dir.write("cube.obj", kCubeObj);
  const std::string path = dir.write("ortho.scene",
                                     "mesh cube.obj\n"
                                     "view top eye 0.5 10 0.6 target 0.5 0 0.5 ortho 3 near 0.5\n"
                                     "view persp eye 0 2 8 target 0 0.5 0\n");
  Scene scene;
  const Status s = loadScene(path, scene);
  ASSERT_TRUE(s) << s.message;
  ASSERT_EQ(scene.views.size(), 2u);
  const View& top = scene.views[0];
  EXPECT_TRUE(top.orthographic());
  EXPECT_EQ(top.orthoHeight, 3.0);
  EXPECT_EQ(top.nearDistance, 0.5);
  // The cube's lowest corner (y = 0) lies ~10 below the eye: the far plane 1% beyond it.
  EXPECT_GT(top.orthoFar, 10.0);
  EXPECT_LT(top.orthoFar, 10.2);
  EXPECT_FALSE(scene.views[1].orthographic());

  const Camera cam = makeCamera(top, 64, 32, INFINITY, ClipDepth::ZeroToOne, true);
  EXPECT_EQ(cam.kind, ProjectionKind::Orthographic);
  DepthModel model;
  ASSERT_TRUE(analyze(cam, model));
  EXPECT_NEAR(model.nearDistance, 0.5, 1e-9);
  EXPECT_NEAR(model.farDistance, top.orthoFar, 1e-9);
  // Orthographic: y_ndc = y / halfHeight, halfHeight = 1.5; the aspect 2 widens x.
  EXPECT_NEAR(cam.projection[5], 1.0 / 1.5, 1e-12);
  EXPECT_NEAR(cam.projection[0], 1.0 / 3.0, 1e-12);
  EXPECT_EQ(makeCamera(scene.views[1], 64, 32, INFINITY, ClipDepth::ZeroToOne, true).kind,
            ProjectionKind::Perspective);
}

// ---- syntax: each text with the exact message parseSceneFile gives for it

struct SyntaxCase {
  std::string text;
  std::string message;  // after "s.scene"
};

void PrintTo(const SyntaxCase& c, std::ostream* os) { *os << test::escapedText(c.text); }

class SceneFileSyntax : public ::testing::TestWithParam<SyntaxCase> {};

TEST_P(SceneFileSyntax, IsRejectedWithItsLine) {
  SceneFile file;
  file.views.resize(3);
  const Status s = parseSceneFile(GetParam().text, "dir/s.scene", file);
  EXPECT_EQ(s.code, StatusCode::InvalidInput);
  EXPECT_EQ(s.message, "dir/s.scene" + GetParam().message);
  EXPECT_EQ(file.views.size(), 3u) << "the output changed on error";
}

const std::string kM = "mesh a.obj\n";  // line 1 of most cases
const std::string kV = "view v eye 0 1 5 target 0 0 0";

INSTANTIATE_TEST_SUITE_P(
    Cases, SceneFileSyntax,
    ::testing::Values(
        SyntaxCase{"", ": has no mesh line"},
        SyntaxCase{"# nothing but a comment\n\n", ": has no mesh line"},
        SyntaxCase{kM + "camera x\n", ":2: unknown keyword 'camera' (expected mesh, transform, view or units)"},
        SyntaxCase{"Mesh a.obj\n", ":1: unknown keyword 'Mesh' (expected mesh, transform, view or units)"},
        SyntaxCase{kM + "units\n", ":2: units takes one word (m, cm, mm, in, ft or auto)"},
        SyntaxCase{kM + "units mm cm\n", ":2: units takes one word (m, cm, mm, in, ft or auto)"},
        SyntaxCase{kM + "units km\n", ":2: unknown unit 'km' (expected m, cm, mm, in, ft or auto)"},
        SyntaxCase{kM + "units MM\n", ":2: unknown unit 'MM' (expected m, cm, mm, in, ft or auto)"},
        SyntaxCase{"units mm\n" + kM + "units cm\n", ":3: units given twice (first on dir/s.scene:1)"},
        SyntaxCase{"mesh\n", ":1: mesh takes one path (quote a path with spaces), got 0 words"},
        SyntaxCase{"mesh a b.obj\n", ":1: mesh takes one path (quote a path with spaces), got 2 words"},
        SyntaxCase{"mesh \"\"\n", ":1: mesh: empty path"},
        SyntaxCase{"mesh a.fbx\n", ":1: 'a.fbx' is not a mesh file (.gltf, .glb, .obj, .ply)"},
        SyntaxCase{"mesh other.scene\n", ":1: 'other.scene' is not a mesh file (.gltf, .glb, .obj, .ply)"},
        SyntaxCase{"mesh \"a.obj\n", ":1: unterminated quoted string"},
        SyntaxCase{"mesh \"a\"b.obj\n", ":1: text right after a closing quote"},
        SyntaxCase{kM + std::string("mesh a\0.obj\n", 13), ":2: contains a NUL byte"},
        SyntaxCase{"transform scale 2\n" + kM, ":1: transform before any mesh line (it applies to the mesh above it)"},
        SyntaxCase{kM + "transform\n", ":2: transform needs at least one of scale, rotate-y, translate, matrix"},
        SyntaxCase{kM + "transform shear 1\n", ":2: unknown transform 'shear' (expected scale, rotate-y, translate or matrix)"},
        SyntaxCase{kM + "transform scale 1 2\n", ":2: scale takes 1 or 3 numbers, got 2"},
        SyntaxCase{kM + "transform scale 1 0 1\n", ":2: scale 0 would flatten the mesh"},
        SyntaxCase{kM + "transform rotate-y\n", ":2: rotate-y takes 1 number (degrees), got 0"},
        SyntaxCase{kM + "transform translate 1 2 translate 1 2 3\n", ":2: translate takes 3 numbers, got 2"},
        SyntaxCase{kM + "transform translate 1 x 2\n", ":2: 'x' is not a number"},
        SyntaxCase{kM + "transform translate 1 2m 2\n", ":2: '2m' is not a number"},
        SyntaxCase{kM + "transform translate 1 2 3 shear 1\n", ":2: unknown transform 'shear' (expected scale, rotate-y, translate or matrix)"},
        SyntaxCase{kM + "transform translate 1 2 3 4\n", ":2: translate takes 3 numbers, got 4"},
        SyntaxCase{kM + "transform translate 1 2\n", ":2: translate takes 3 numbers, got 2"},
        SyntaxCase{kM + "view v eye 0 x 1 target 0 0 0\n", ":2: 'x' is not a number"},
        SyntaxCase{kM + "transform translate 1 nan 2\n", ":2: 'nan' is not a finite number"},
        SyntaxCase{kM + "transform rotate-y inf\n", ":2: 'inf' is not a finite number"},
        SyntaxCase{kM + "transform translate 1 1e999 2\n", ":2: number '1e999' is out of range"},
        SyntaxCase{kM + "transform matrix 1 2 3\n", ":2: matrix takes 16 numbers (4 rows of 4), got 3"},
        SyntaxCase{kM + "transform matrix 1 0 0 0  0 1 0 0  0 0 1 0  0 0 1 1\n",
                   ":2: matrix: the last row must be 0 0 0 1 (an affine transform)"},
        SyntaxCase{kM + "transform matrix 1 0 0 0  2 0 0 0  0 0 1 0  0 0 0 1\n", ":2: matrix: singular (determinant 0)"},
        SyntaxCase{kM + "transform scale 1e200\ntransform scale 1e200\n", ":3: the transform overflows (a non-finite matrix)"},
        SyntaxCase{kM + "view\n", ":2: view needs a name"},
        SyntaxCase{kM + "view v target 0 0 0\n", ":2: view 'v' has no eye"},
        SyntaxCase{kM + "view v eye 0 0 1\n", ":2: view 'v' has no target"},
        SyntaxCase{kM + "view v eye 0 0 1 2 target 0 0 0\n", ":2: eye takes 3 numbers, got 4"},
        SyntaxCase{kM + "view v eye 0 0 1 target\n", ":2: target takes 3 numbers, got 0"},
        SyntaxCase{kM + "view v eye 0 0 1 eye 0 0 2 target 0 0 0\n", ":2: view property 'eye' given twice"},
        SyntaxCase{kM + kV + " zoom 2\n", ":2: unknown view property 'zoom' (expected eye, target, fovy, ortho, near)"},
        SyntaxCase{kM + kV + " ortho 0\n", ":2: ortho 0: the view height must be greater than 0"},
        SyntaxCase{kM + kV + " ortho -2\n", ":2: ortho -2: the view height must be greater than 0"},
        SyntaxCase{kM + kV + " ortho\n", ":2: ortho takes 1 number, got 0"},
        SyntaxCase{kM + kV + " ortho inf\n", ":2: 'inf' is not a finite number"},
        SyntaxCase{kM + kV + " ortho 2 ortho 3\n", ":2: view property 'ortho' given twice"},
        SyntaxCase{kM + kV + " ortho 2 fovy 40\n",
                   ":2: view 'v' has both fovy and ortho (a perspective or an orthographic view: pick one)"},
        SyntaxCase{kM + "transform ortho 2\n", ":2: unknown transform 'ortho' (expected scale, rotate-y, translate or matrix)"},
        SyntaxCase{kM + kV + " fovy 180\n", ":2: fovy 180 is outside (0, 180) degrees"},
        SyntaxCase{kM + kV + " fovy 0\n", ":2: fovy 0 is outside (0, 180) degrees"},
        SyntaxCase{kM + kV + " fovy 30 fovy 40\n", ":2: view property 'fovy' given twice"},
        SyntaxCase{kM + kV + " near 0\n", ":2: near 0 must be greater than 0"},
        SyntaxCase{kM + kV + " near -1\n", ":2: near -1 must be greater than 0"},
        SyntaxCase{kM + kV + " near 1 near 2\n", ":2: view property 'near' given twice"},
        SyntaxCase{kM + "view v eye 1 1 1 target 1 1 1\n", ":2: view 'v': eye and target are the same point"},
        SyntaxCase{kM + "view v eye 1e200 0 0 target -1e200 0 0\n", ":2: view 'v': eye and target are too far apart"},
        SyntaxCase{kM + "view v eye 0 5 0 target 0 -1 0\n",
                   ":2: view 'v' looks straight up or down (up is +y): move the target sideways a little"},
        SyntaxCase{kM + kV + "\n# another\n" + kV + "\n", ":4: view 'v' is defined twice (first on line 2)"}));

TEST(SceneFile, CommentsQuotesAndAbsolutePaths) {
  SceneFile file;
  const Status s = parseSceneFile("mesh a#b.obj # a comment\n"
                                  "mesh \"with space.glb\"\t# another\n"
                                  "mesh /abs/c.PLY\n"
                                  "#mesh d.obj\n"
                                  "view v eye 0 1 5 target 0 0 0 # the last line has no newline",
                                  "dir/s.scene", file);
  ASSERT_TRUE(s) << s.message;
  ASSERT_EQ(file.meshes.size(), 3u);
  EXPECT_EQ(file.meshes[0].path, "dir/a#b.obj");
  EXPECT_EQ(file.meshes[1].path, "dir/with space.glb");
  EXPECT_EQ(file.meshes[2].path, "/abs/c.PLY");
  EXPECT_EQ(file.meshes[2].line, 3);
  ASSERT_EQ(file.views.size(), 1u);
  EXPECT_EQ(file.views[0].line, 5);
  EXPECT_FALSE(file.views[0].nearDistance.has_value());
}

// ---- loading: the scene file's own errors and its meshes' errors, prefixed with its line

TEST(SceneFile, LoadErrorsNameTheSceneLineAndTheMesh) {
  TempDir dir;
  dir.write("cube.obj", kCubeObj);
  dir.write("bad.obj", "v 0 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 9\n");
  auto load = [&](const std::string& name, const std::string& text) {
    Scene scene;
    scene.name = "untouched";
    const Status s = loadScene(dir.write(name, text), scene);
    EXPECT_EQ(scene.name, "untouched");
    return s;
  };
  Status s = load("refers.scene", "mesh cube.obj\nmesh missing.obj\n");
  EXPECT_EQ(s.code, StatusCode::IoError);
  EXPECT_EQ(s.message, dir.file("refers.scene") + ":2: " + dir.file("missing.obj") + ": no such file");

  s = load("bad.scene", "# a comment\nmesh bad.obj\n");
  EXPECT_EQ(s.code, StatusCode::InvalidInput);
  EXPECT_EQ(s.message, dir.file("bad.scene") + ":2: " + dir.file("bad.obj") +
                           ": OBJ line 4: a face refers to vertex 9, but there are only 3 vertices");

  s = load("far.scene", "mesh cube.obj\ntransform scale 1e39\n");
  EXPECT_EQ(s.code, StatusCode::InvalidInput);
  EXPECT_EQ(s.message.rfind(dir.file("far.scene") + ":1: the transform takes vertex ", 0), 0u) << s.message;
  EXPECT_NE(s.message.find(" of " + dir.file("cube.obj") + " beyond the range of a float"), std::string::npos) << s.message;

  s = load("syntax.scene", "mesh cube.obj\nview v\n");
  EXPECT_EQ(s.message, dir.file("syntax.scene") + ":2: view 'v' has no eye");

  s = load("empty.scene", "");
  EXPECT_EQ(s.message, dir.file("empty.scene") + ": has no mesh line");

  const std::string big = dir.write("big.scene", std::string(kMaxSceneFileBytes + 1, '#'));
  Scene scene;
  s = loadScene(big, scene);
  EXPECT_EQ(s.code, StatusCode::IoError);
  EXPECT_EQ(s.message, big + ": is 1048577 bytes, more than the limit of 1048576");

  std::filesystem::create_directories(dir.file("folder.scene"));
  s = loadScene(dir.file("folder.scene"), scene);
  EXPECT_EQ(s.message, dir.file("folder.scene") + ": is a directory, not a file");
}

}  // namespace
}  // namespace sao::scenes
