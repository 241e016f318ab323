// Mesh files (sao/scenes/mesh_file.h: glTF through tinygltf) and the default view (default_view.h):
// real models from assimp-testmodels, hand-written files on disk and in memory, and every
// rejection with its message.
#include <sys/stat.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "sao/raytrace/raytrace.h"
#include "sao/scenes/default_view.h"
#include "sao/scenes/mesh_file.h"
#include "sao/scenes/scene.h"
#include "test_models.h"

namespace sao::scenes {
namespace {

using test::kAssimpModels;
using test::kCubeObj;
using test::TempDir;

void bounds(const Mesh& mesh, glm::dvec3& lo, glm::dvec3& hi) {
  lo = glm::dvec3(INFINITY);
  hi = glm::dvec3(-INFINITY);
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
}

// Every vertex lies in front of the near plane and inside the view's frustum for a square image,
// and ray casting a 64x64 image from the view hits the mesh in at least 5% of the pixels.
void expectViewSeesMesh(const Scene& scene, const View& view) {
  const glm::dmat4 m = viewMatrix(view);
  const double t = std::tan(view.fovyRadians / 2) * (1 + 1e-9);
  for (std::size_t i = 0; i < scene.mesh.positions.size(); ++i) {
    const glm::dvec3 c = glm::dvec3(m * glm::dvec4(glm::dvec3(scene.mesh.positions[i]), 1.0));
    ASSERT_LT(c.z, -view.nearDistance) << "vertex " << i << " is behind the near plane";
    ASSERT_LE(std::abs(c.x), -c.z * t) << "vertex " << i << " is left or right of the frustum";
    ASSERT_LE(std::abs(c.y), -c.z * t) << "vertex " << i << " is above or below the frustum";
  }
  std::unique_ptr<raytrace::RayScene> rays;
  ASSERT_TRUE(raytrace::RayScene::create(scene.mesh, rays));
  const Camera camera = makeCamera(view, 64, 64, INFINITY, ClipDepth::ZeroToOne, true);
  raytrace::Primary primary;
  ASSERT_TRUE(raytrace::castPrimary(*rays, view, camera, DepthFormat::D32F, primary));
  std::size_t hits = 0;
  for (std::uint32_t y = 0; y < 64; ++y)
    for (std::uint32_t x = 0; x < 64; ++x) hits += primary.position.at(x, y, 3) != 0.0f;
  EXPECT_GT(hits, 64u * 64u / 20) << "the default view sees the mesh in only " << hits << " of 4096 pixels";
}

void requireTestModels() {
  if (!std::filesystem::is_directory(kAssimpModels / "glTF2"))
    GTEST_SKIP() << kAssimpModels << " is missing: install assimp-testmodels (ci/setup.sh does)";
}

// ---- real models

struct RealModel {
  const char* path;
  std::size_t minTriangles;
};

TEST(MeshFile, LoadsRealModelsWithAViewThatSeesThem) {
  requireTestModels();
  for (const RealModel& model : {RealModel{"glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", 100000},
                                 RealModel{"OBJ/WusonOBJ.obj", 3000}, RealModel{"PLY/Wuson.ply", 3000}}) {
    SCOPED_TRACE(model.path);
    const std::string path = (kAssimpModels / model.path).string();
    Scene scene;
    const Status s = loadScene(path, scene);
    ASSERT_TRUE(s) << s.message;
    EXPECT_GE(scene.mesh.triangleCount(), model.minTriangles);
    EXPECT_TRUE(validateMesh(scene.mesh, path));
    glm::dvec3 lo, hi;
    bounds(scene.mesh, lo, hi);
    for (int k = 0; k < 3; ++k) {
      EXPECT_TRUE(std::isfinite(lo[k]) && std::isfinite(hi[k]));
      EXPECT_LT(lo[k], hi[k]);
    }
    EXPECT_EQ(scene.name, std::filesystem::path(path).filename().string());
    // 2CylinderEngine.glb also has a camera, view 1 (gltf_cameras_test.cpp).
    ASSERT_EQ(scene.views.size(), std::string_view(model.path).ends_with(".glb") ? 2u : 1u);
    EXPECT_EQ(scene.views[0].name, "default");
    EXPECT_NEAR(scene.views[0].nearDistance, glm::length(hi - lo) / 100, 1e-6 * glm::length(hi - lo));
    EXPECT_NEAR(glm::length(scene.views[0].target - (lo + hi) * 0.5), 0.0, 1e-9 * glm::length(hi - lo));
    expectViewSeesMesh(scene, scene.views[0]);
  }
}

TEST(MeshFile, ObjAndPlyOfTheSameModelAgree) {
  requireTestModels();
  Mesh obj, ply;
  ASSERT_TRUE(loadMeshFile((kAssimpModels / "OBJ/WusonOBJ.obj").string(), obj));
  ASSERT_TRUE(loadMeshFile((kAssimpModels / "PLY/Wuson.ply").string(), ply));
  EXPECT_EQ(obj.triangleCount(), ply.triangleCount());
  EXPECT_EQ(obj.triangleCount(), 3732u);
  EXPECT_EQ(obj.positions.size(), 2117u);   // each file's own vertex list
  EXPECT_EQ(ply.positions.size(), 11184u);  // (the PLY repeats vertices with other normals)
  glm::dvec3 lo1, hi1, lo2, hi2;
  bounds(obj, lo1, hi1);
  bounds(ply, lo2, hi2);
  EXPECT_NEAR(glm::length(lo1 - lo2), 0.0, 1e-4);
  EXPECT_NEAR(glm::length(hi1 - hi2), 0.0, 1e-4);
}

// ---- hand-written files

TEST(MeshFile, ObjIsTriangulatedAndVerticesJoined) {
  TempDir dir;
  Mesh mesh;
  const Status s = loadMeshFile(dir.write("cube.OBJ", kCubeObj), mesh);  // the extension in any case
  ASSERT_TRUE(s) << s.message;
  EXPECT_EQ(mesh.triangleCount(), 12u);
  EXPECT_EQ(mesh.positions.size(), 8u);
  glm::dvec3 lo, hi;
  bounds(mesh, lo, hi);
  EXPECT_EQ(lo, glm::dvec3(0));
  EXPECT_EQ(hi, glm::dvec3(1));
}

// A glTF triangle (0,0,0) (1,0,0) (0,1,0) in a node that translates by (10, 0, 0) and scales by
// 2; its buffer at `uri`.
std::string triangleGltf(std::string_view uri) {
  return R"({
  "asset": {"version": "2.0"},
  "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0, "translation": [10, 0, 0], "scale": [2, 2, 2]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "buffers": [{"byteLength": 36, "uri": ")" + std::string(uri) + R"("}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}]
})";
}
// The same 9 floats as a data URI.
const std::string kTriangleGltf =
    triangleGltf("data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA");

constexpr std::string_view kTrianglePly =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

std::span<const std::uint8_t> bytes(std::string_view text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

TEST(MeshFile, GltfNodeTransformIsApplied) {
  TempDir dir;
  for (int fromMemory = 0; fromMemory < 2; ++fromMemory) {
    Mesh mesh;
    const Status s = fromMemory ? loadMeshFromMemory(bytes(kTriangleGltf), "gltf", "triangle", mesh)
                                : loadMeshFile(dir.write("triangle.gltf", kTriangleGltf), mesh);
    ASSERT_TRUE(s) << s.message;
    ASSERT_EQ(mesh.triangleCount(), 1u);
    glm::dvec3 lo, hi;
    bounds(mesh, lo, hi);
    EXPECT_EQ(lo, glm::dvec3(10, 0, 0));
    EXPECT_EQ(hi, glm::dvec3(12, 2, 0));
  }
}

TEST(MeshFile, EveryFormatFromMemory) {
  Mesh obj, ply, gltf;
  ASSERT_TRUE(loadMeshFromMemory(bytes(kCubeObj), "obj", "cube", obj));
  EXPECT_EQ(obj.triangleCount(), 12u);
  ASSERT_TRUE(loadMeshFromMemory(bytes(kTrianglePly), "ply", "triangle", ply));
  EXPECT_EQ(ply.triangleCount(), 1u);
  ASSERT_TRUE(loadMeshFromMemory(bytes(kTriangleGltf), "gltf", "triangle", gltf));
  EXPECT_EQ(gltf.triangleCount(), 1u);

  Mesh untouched;
  untouched.positions = {{1, 2, 3}};
  Status s = loadMeshFromMemory(bytes(kCubeObj), "fbx", "cube", untouched);
  EXPECT_EQ(s.code, StatusCode::UnsupportedFormat);
  EXPECT_EQ(s.message, "cube: unknown format 'fbx' (mesh formats: gltf, glb, obj, ply)");
  s = loadMeshFromMemory({}, "obj", "nothing", untouched);
  EXPECT_EQ(s.message, "nothing: is empty");
  EXPECT_EQ(untouched.positions.size(), 1u);
}

// A glTF buffer outside the data: read next to a file (a regular file), never from memory (no
// file is opened for data in memory), never from a FIFO (it would block).
TEST(MeshFile, ExternalBuffersOnlyFromRegularFilesNextToAFile) {
  TempDir dir;
  const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  dir.write("triangle.bin", std::string_view(reinterpret_cast<const char*>(triangle), sizeof triangle));
  const std::string external = triangleGltf("triangle.bin");
  Mesh mesh;
  Status s = loadMeshFile(dir.write("external.gltf", external), mesh);
  ASSERT_TRUE(s) << s.message;
  EXPECT_EQ(mesh.triangleCount(), 1u);

  s = loadMeshFromMemory(bytes(external), "gltf", "in-memory", mesh);
  EXPECT_EQ(s.code, StatusCode::IoError);
  EXPECT_EQ(s.message, "in-memory: glTF: buffers[0].uri: could not open the referenced file \"triangle.bin\" (no file "
                       "is opened for data in memory)");

  const std::string absolute = triangleGltf(dir.file("triangle.bin"));
  s = loadMeshFromMemory(bytes(absolute), "gltf", "in-memory", mesh);
  EXPECT_EQ(s.code, StatusCode::IoError) << "an absolute path is not opened from memory either";

  ASSERT_EQ(mkfifo(dir.file("pipe.bin").c_str(), 0600), 0);
  const std::string fifo = triangleGltf("pipe.bin");
  s = loadMeshFile(dir.write("fifo.gltf", fifo), mesh);
  EXPECT_EQ(s.code, StatusCode::IoError);
  EXPECT_EQ(s.message,
            dir.file("fifo.gltf") + ": glTF: buffers[0].uri: could not open the referenced file \"pipe.bin\" (not a regular file)");
  const std::string missing = triangleGltf("missing.bin");
  s = loadMeshFile(dir.write("missing.gltf", missing), mesh);
  EXPECT_EQ(s.message, dir.file("missing.gltf") +
                           ": glTF: buffers[0].uri: could not open the referenced file \"missing.bin\" (no such file)");
  dir.write("short.bin", std::string_view(reinterpret_cast<const char*>(triangle), 32));
  s = loadMeshFile(dir.write("short.gltf", triangleGltf("short.bin")), mesh);
  EXPECT_EQ(s.message, dir.file("short.gltf") + ": glTF: buffers[0].uri: could not open the referenced file "
                                                "\"short.bin\" (it has 32 bytes, but byteLength is 36)");
}

// Only geometry is read: an image is neither decoded (its data is not an image at all here) nor
// opened (the file it names does not exist), whether in a data URI, a file or a buffer view.
TEST(MeshFile, ImagesAreNeitherDecodedNorOpened) {
  TempDir dir;
  const std::string images = R"("images": [{"uri": "data:image/png;base64,bm90IGEgUE5H"}, {"uri": "missing.png"},
                                           {"bufferView": 0, "mimeType": "image/png"}],
  "textures": [{"source": 0}, {"source": 1}, {"source": 2}], )";
  std::string gltf = kTriangleGltf;
  gltf.insert(gltf.find("\"scene\""), images);
  Mesh fromMemory, fromFile;
  Status s = loadMeshFromMemory(bytes(gltf), "gltf", "mem", fromMemory);
  ASSERT_TRUE(s) << s.message;
  s = loadMeshFile(dir.write("images.gltf", gltf), fromFile);
  ASSERT_TRUE(s) << s.message;
  EXPECT_EQ(fromMemory.triangleCount(), 1u);
  EXPECT_EQ(fromFile.positions, fromMemory.positions);
}

// Primitives without POSITION, and line loops, are refused (assimp 5.2, the reader before
// tinygltf, dereferenced a null pointer for a line loop without positions, found by fuzzing).
TEST(MeshFile, GltfPrimitiveWithoutPositionsOrALineLoopIsRefused) {
  std::string gltf = kTriangleGltf;
  const std::string positions = "\"POSITION\": 0}";
  gltf.replace(gltf.find(positions), positions.size(), "\"NORMAL\": 0}, \"mode\": 2");
  Mesh mesh;
  const Status s = loadMeshFromMemory(bytes(gltf), "gltf", "mem", mesh);
  EXPECT_EQ(s.code, StatusCode::IoError);
  EXPECT_EQ(s.message, "mem: glTF: mesh 0 primitive 0 has no POSITION attribute");
  // A line loop with positions: only triangles are read; a line loop is refused rather than dropped.
  std::string loop = kTriangleGltf;
  loop.replace(loop.find(positions), positions.size(), "\"POSITION\": 0}, \"mode\": 2");
  const Status l = loadMeshFromMemory(bytes(loop), "gltf", "mem", mesh);
  EXPECT_EQ(l.code, StatusCode::IoError);
  EXPECT_EQ(l.message, "mem: glTF: mesh 0 primitive 0 is a line loop (mode 2); only triangles are read");
}

// A data URI's header of more than 126 characters is refused (assimp 5.2 kept offsets into it in a
// signed char and read outside the string, found by fuzzing); a long payload is fine.
TEST(MeshFile, GltfDataUriWithALongHeaderIsRefused) {
  const std::string payload = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";
  Mesh mesh;
  // glTF 2.0's media type with a long parameter (other media types are refused on their own).
  const std::string longType =
      triangleGltf("data:application/octet-stream;" + std::string(97, 'x') + ";base64," + payload);
  Status s = loadMeshFromMemory(bytes(longType), "gltf", "mem", mesh);
  EXPECT_EQ(s.code, StatusCode::IoError);
  EXPECT_EQ(s.message, "mem: glTF: buffers[0].uri: the data URI's header (before its comma) is 134 characters long, "
                       "more than 126");
  // The comma at 126: the length is fine, but tinygltf reads no media type parameters.
  const std::string limit = triangleGltf("data:application/octet-stream;" + std::string(89, 'x') + ";base64," + payload);
  s = loadMeshFromMemory(bytes(limit), "gltf", "mem", mesh);
  EXPECT_EQ(s.message, "mem: glTF: buffers[0].uri: the data URI's header 'data:application/octet-stream;" +
                           std::string(34, 'x') + "...' has parameters; only 'data:application/octet-stream;base64' "
                           "and 'data:application/gltf-buffer;base64' are read");
  // An image's data URI with its comma at 126 loads (images are not decoded).
  std::string image = kTriangleGltf;
  image.insert(image.find("\"scene\""),
               R"("images": [{"uri": "data:image/png;)" + std::string(104, 'x') + R"(;base64,AAAA"}], )");
  s = loadMeshFromMemory(bytes(image), "gltf", "mem", mesh);
  EXPECT_TRUE(s) << s.message;
  image.replace(image.find(std::string(104, 'x')), 104, std::string(105, 'x'));
  s = loadMeshFromMemory(bytes(image), "gltf", "mem", mesh);
  EXPECT_EQ(s.message, "mem: glTF: images[0].uri: the data URI's header (before its comma) is 127 characters long, "
                       "more than 126");
}

// ---- rejections: the code, the exact message, and the output untouched

struct Rejection {
  std::string path;
  StatusCode code;
  std::string message;  // expected in full
};

void expectRejected(const Rejection& r) {
  SCOPED_TRACE(r.path);
  Mesh mesh;
  mesh.positions = {{7, 7, 7}};
  const Status s = loadMeshFile(r.path, mesh);
  EXPECT_EQ(s.code, r.code) << s.message;
  EXPECT_EQ(s.message, r.message);
  EXPECT_EQ(mesh.positions.size(), 1u) << "the output changed on error";
}

TEST(MeshFile, FileProblemsAreRejected) {
  TempDir dir;
  std::filesystem::create_directories(dir.file("folder.glb"));
  ASSERT_EQ(mkfifo(dir.file("fifo.obj").c_str(), 0600), 0);
  const std::string missing = dir.file("missing.glb");
  expectRejected({missing, StatusCode::IoError, missing + ": no such file"});
  expectRejected({dir.file("folder.glb"), StatusCode::IoError, dir.file("folder.glb") + ": is a directory, not a file"});
  expectRejected({dir.file("fifo.obj"), StatusCode::IoError,
                  dir.file("fifo.obj") + ": is not a regular file (a FIFO, socket or device)"});
  for (const char* name : {"empty.glb", "empty.gltf", "empty.obj", "empty.ply"})
    expectRejected({dir.write(name, ""), StatusCode::IoError, dir.file(name) + ": is empty"});
  const std::string fbx = dir.write("model.fbx", kCubeObj);
  expectRejected({fbx, StatusCode::UnsupportedFormat, fbx + ": unknown extension '.fbx' (mesh files: .gltf, .glb, .obj, .ply)"});
  const std::string none = dir.write("model", kCubeObj);
  expectRejected({none, StatusCode::UnsupportedFormat, none + ": has no extension (mesh files: .gltf, .glb, .obj, .ply)"});
}

TEST(MeshFile, GarbageBytesAreRejected) {
  TempDir dir;
  std::mt19937 random(20240601);
  std::string garbage(4096, '\0');
  for (char& c : garbage) c = char(random());
  const std::string glb = dir.write("garbage.glb", garbage), obj = dir.write("garbage.obj", garbage),
                    ply = dir.write("garbage.ply", garbage), gltf = dir.write("garbage.gltf", garbage);
  expectRejected({glb, StatusCode::IoError, glb + ": binary glTF: does not start with the magic \"glTF\""});
  expectRejected({gltf, StatusCode::IoError, gltf + ": not valid JSON (at byte 1)"});
  expectRejected({obj, StatusCode::InvalidInput, obj + ": has no triangles"});  // no v or f line in it
  expectRejected({ply, StatusCode::IoError, ply + ": PLY: not a PLY file (the first line is not 'ply')"});
}

std::string le32(std::uint32_t v) { return std::string{char(v), char(v >> 8), char(v >> 16), char(v >> 24)}; }

// A binary glTF: header, JSON chunk (padded to 4 bytes), optional BIN chunk.
std::string glb(std::string json, std::string bin, std::uint32_t declaredLength = 0, std::uint32_t declaredJson = 0) {
  while (json.size() % 4) json += ' ';
  std::string body = le32(declaredJson ? declaredJson : std::uint32_t(json.size())) + "JSON" + json;
  if (!bin.empty()) body += le32(std::uint32_t(bin.size())) + std::string("BIN\0", 4) + bin;
  return "glTF" + le32(2) + le32(declaredLength ? declaredLength : std::uint32_t(12 + body.size())) + body;
}

// Binary glTF chunks must fit the file and hold valid JSON before tinygltf sees them (assimp 5.2
// allocated a chunk's declared size first: 2.9 GB for a 600-byte file found by fuzzing; tinygltf
// 2.7.0 lets a BIN chunk run 8 bytes past the data).
TEST(MeshFile, BinaryGltfContainerIsChecked) {
  TempDir dir;
  const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::string bin(reinterpret_cast<const char*>(triangle), sizeof triangle);
  std::string json = triangleGltf("");
  json.replace(json.find(", \"uri\": \"\""), 11, "");
  Mesh mesh;
  const std::string good = dir.write("good.glb", glb(json, bin));
  Status s = loadMeshFile(good, mesh);
  ASSERT_TRUE(s) << s.message;
  EXPECT_EQ(mesh.triangleCount(), 1u);

  const std::string longFile = dir.write("long.glb", glb(json, bin, 0x7fffffff));
  expectRejected({longFile, StatusCode::IoError,
                  longFile + ": binary glTF: the header declares 2147483647 bytes, the file has " +
                      std::to_string(std::filesystem::file_size(longFile))});
  const std::string longJson = dir.write("json.glb", glb(json, bin, 0, 0xac000210));
  const auto size = std::filesystem::file_size(longJson);
  expectRejected({longJson, StatusCode::IoError,
                  longJson + ": binary glTF: the JSON chunk declares 2885681680 bytes, " + std::to_string(size - 20) + " follow"});
  std::string shortBin = glb(json, bin);
  shortBin.resize(shortBin.size() - 8);
  const std::string binFile = dir.write("bin.glb", shortBin);
  expectRejected({binFile, StatusCode::IoError, binFile + ": binary glTF: the header declares " +
                                                    std::to_string(shortBin.size() + 8) + " bytes, the file has " +
                                                    std::to_string(shortBin.size())});
  std::string shortBin2 = glb(json, bin);
  shortBin2.resize(shortBin2.size() - 8);
  shortBin2.replace(8, 4, le32(std::uint32_t(shortBin2.size())));
  const std::string binFile2 = dir.write("bin2.glb", shortBin2);
  expectRejected({binFile2, StatusCode::IoError, binFile2 + ": binary glTF: the BIN chunk declares 36 bytes, 28 follow"});
  const std::string badJson = dir.write("badjson.glb", glb("{\"asset\": ", bin));
  expectRejected({badJson, StatusCode::IoError, badJson + ": not valid JSON (at byte 13)"});
  // The same checks from memory.
  const std::string bytesLong = glb(json, bin, 0, 0xac000210);
  s = loadMeshFromMemory({reinterpret_cast<const std::uint8_t*>(bytesLong.data()), bytesLong.size()}, "glb", "mem", mesh);
  EXPECT_EQ(s.message, "mem: binary glTF: the JSON chunk declares 2885681680 bytes, " + std::to_string(bytesLong.size() - 20) + " follow");
  const std::string v1 = dir.write("v1.glb", std::string("glTF\x01\x00\x00\x00", 8) + le32(20) + le32(0) + le32(0));
  expectRejected({v1, StatusCode::IoError, v1 + ": binary glTF: version 1 is not supported (glTF 2.0 only)"});
  const std::string header = dir.write("header.glb", std::string("glTF\x02\x00\x00\x00", 8) + le32(40) + "garbage");
  expectRejected({header, StatusCode::IoError, header + ": binary glTF: the header declares 40 bytes, the file has 19"});
}

TEST(MeshFile, BadGeometryIsRejected) {
  TempDir dir;
  const std::string inf = dir.write("inf.obj", "v 1e39 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n");
  expectRejected({inf, StatusCode::InvalidInput, inf + ": vertex 0 has a non-finite coordinate (inf, 0, 0)"});
  std::string nanPly(kTrianglePly);
  nanPly.replace(nanPly.find("end_header\n0 0 0") + 11, 5, "0 nan 0");
  const std::string nan = dir.write("nan.ply", nanPly);
  expectRejected({nan, StatusCode::InvalidInput, nan + ": vertex 0 has a non-finite coordinate (0, nan, 0)"});
  const std::string objIndex = dir.write("index.obj", "v 0 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 9\n");
  expectRejected({objIndex, StatusCode::InvalidInput,
                  objIndex + ": OBJ line 4: a face refers to vertex 9, but there are only 3 vertices"});
  std::string plyIndexText(kTrianglePly);
  plyIndexText.replace(plyIndexText.size() - 2, 1, "7");
  const std::string plyIndex = dir.write("index.ply", plyIndexText);
  expectRejected({plyIndex, StatusCode::InvalidInput,
                  plyIndex + ": PLY: face 0 refers to vertex 7, but there are only 3 vertices"});
  const std::string lines = dir.write("lines.obj", "v 0 0 0\nv 0 1 0\nv 1 1 0\nl 1 2\nl 2 3\n");
  expectRejected({lines, StatusCode::InvalidInput, lines + ": has no triangles"});
  const std::string point = dir.write("point.obj", "v 1 2 3\nv 1 2 3\nv 1 2 3\nf 1 2 3\n");
  expectRejected({point, StatusCode::InvalidInput, point + ": all its triangles are at one point (1, 2, 3)"});
}

TEST(MeshFile, ValidateMeshNamesEachProblem) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.indices = {0, 1, 2};
  EXPECT_TRUE(validateMesh(m, "m"));
  auto expectProblem = [](const Mesh& mesh, const std::string& message, std::size_t limit = kMaxMeshTriangles) {
    const Status s = validateMesh(mesh, "m", limit);
    EXPECT_EQ(s.code, StatusCode::InvalidInput);
    EXPECT_EQ(s.message, message);
  };
  Mesh bad = m;
  bad.indices = {0, 1, 5};
  expectProblem(bad, "m: triangle 0 refers to vertex 5, but there are only 3 vertices");
  bad.indices = {0, 1};
  expectProblem(bad, "m: has 2 indices, not a whole number of triangles");
  bad.indices.clear();
  expectProblem(bad, "m: has no triangles");
  bad = m;
  bad.positions[1].y = std::nanf("");
  expectProblem(bad, "m: vertex 1 has a non-finite coordinate (1, nan, 0)");
  bad = m;
  bad.positions[2].z = -INFINITY;
  expectProblem(bad, "m: vertex 2 has a non-finite coordinate (0, 1, -inf)");
  bad = m;
  bad.indices = {0, 1, 2, 2, 1, 0};
  expectProblem(bad, "m: has 2 triangles, more than the limit of 1", 1);
  EXPECT_EQ(kMaxMeshTriangles, 50'000'000u);
}

// ---- loadScene's dispatch

TEST(LoadScene, NamesFilesAndErrors) {
  TempDir dir;
  Scene scene;
  ASSERT_TRUE(loadScene("crease", scene));
  EXPECT_EQ(scene.name, "crease");

  Scene untouched;
  untouched.name = "untouched";
  Status s = loadScene("nope", untouched);
  EXPECT_EQ(s.code, StatusCode::InvalidInput);
  EXPECT_EQ(s.message,
            "unknown built-in scene 'nope' (built-in: sponza-like, sphere-plane, crease, thin, gears), and no file of "
            "that name either");
  s = loadScene(dir.file("model.fbx"), untouched);
  EXPECT_EQ(s.code, StatusCode::UnsupportedFormat);
  EXPECT_EQ(s.message, dir.file("model.fbx") +
                           ": unknown extension '.fbx' (scene files: .scene; mesh files: .gltf, .glb, .obj, .ply)");
  s = loadScene(dir.path().string(), untouched);
  EXPECT_EQ(s.code, StatusCode::IoError);
  EXPECT_EQ(s.message, dir.path().string() + ": is a directory, not a scene or mesh file");
  s = loadScene(dir.file("missing.ply"), untouched);
  EXPECT_EQ(s.message, dir.file("missing.ply") + ": no such file");
  s = loadScene(dir.file("missing.scene"), untouched);
  EXPECT_EQ(s.message, dir.file("missing.scene") + ": no such file");
  EXPECT_EQ(untouched.name, "untouched");

  ASSERT_TRUE(loadScene(dir.write("cube.obj", kCubeObj), scene));
  EXPECT_EQ(scene.name, "cube.obj");
  ASSERT_EQ(scene.views.size(), 1u);
  const View& v = scene.views[0];
  EXPECT_EQ(v.target, glm::dvec3(0.5));
  EXPECT_NEAR(v.fovyRadians, std::acos(-1.0) / 3, 1e-12);
  EXPECT_NEAR(v.nearDistance, std::sqrt(3.0) / 100, 1e-12);
  // The eye is on the (1, 1, 1) diagonal, where the bounding sphere (radius sqrt(3)/2) just fits.
  const glm::dvec3 d = v.eye - v.target;
  EXPECT_NEAR(glm::length(d), std::sqrt(3.0) / 2 / std::sin(std::acos(-1.0) / 6), 1e-9);
  EXPECT_NEAR(d.x, d.y, 1e-12);
  EXPECT_NEAR(d.y, d.z, 1e-12);
  EXPECT_GT(d.x, 0);
  expectViewSeesMesh(scene, v);
}

}  // namespace
}  // namespace sao::scenes
