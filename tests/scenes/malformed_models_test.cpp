// Malformed and odd models from Debian's assimp-testmodels: every one either loads to a mesh that
// passes validateMesh (with a view) or is refused with a Status whose message starts with its
// path; never a crash. The counts are printed (docs/ROBUSTNESS.md section 4.8 quotes them).
#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sao/scenes/mesh_file.h"
#include "sao/scenes/scene.h"
#include "test_models.h"

namespace sao::scenes {
namespace {

namespace fs = std::filesystem;
using test::kAssimpModels;

std::vector<fs::path> filesUnder(const fs::path& dir, bool meshFilesOnly) {
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && (!meshFilesOnly || isMeshFileExtension(e.path().string()))) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

// Loads one file as sao-render would; returns its class: "loaded", "wrong type" (a member of a
// type the glTF 2.0 schema does not allow, named), "tinygltf error" (tinygltf's own message),
// "rejected by sao" (our other checks: empty, no triangles, non-finite, ...) or "unsupported
// extension".
std::string loadOne(const fs::path& file) {
  const std::string path = file.string();
  Scene scene;
  scene.name = "untouched";
  const Status s = loadScene(path, scene);
  if (s) {
    EXPECT_TRUE(validateMesh(scene.mesh, path)) << path;
    // The default view first, then a glTF's cameras (gltf_cameras_test.cpp).
    EXPECT_TRUE(!scene.views.empty() && scene.views[0].name == "default") << path;
    for (const std::string& w : scene.warnings) std::printf("warning: %s\n", w.c_str());
    return "loaded";
  }
  EXPECT_EQ(s.message.rfind(path + ": ", 0), 0u) << "the message does not start with the path: " << s.message;
  EXPECT_GT(s.message.size(), path.size() + 2) << s.message;
  EXPECT_EQ(scene.name, "untouched") << path;
  if (s.code == StatusCode::UnsupportedFormat) return "unsupported extension";
  EXPECT_TRUE(s.code == StatusCode::IoError || s.code == StatusCode::InvalidInput) << toString(s.code);
  if (s.message.find("; glTF 2.0 requires ") != std::string::npos) return "wrong type";
  return s.message.find(": tinygltf: ") != std::string::npos ? "tinygltf error" : "rejected by sao";
}

void report(const char* what, std::size_t tried, const std::map<std::string, int>& classes) {
  std::printf("%s: %zu files tried:", what, tried);
  for (const auto& [name, n] : classes) std::printf(" %s %d;", name.c_str(), n);
  std::printf("\n");
}

void requireTestModels() {
  if (!fs::is_directory(kAssimpModels / "glTF2"))
    GTEST_SKIP() << kAssimpModels << " is missing: install assimp-testmodels (ci/setup.sh does)";
}

// Every file (the .bin buffers and .png textures included) under the two folders of deliberately
// malformed glTF.
TEST(MalformedModels, EveryFileInWrongTypesAndSchemaFailures) {
  requireTestModels();
  std::map<std::string, int> classes;
  std::size_t tried = 0;
  for (const char* dir : {"glTF2/wrongTypes", "glTF2/SchemaFailures"}) {
    for (const fs::path& file : filesUnder(kAssimpModels / dir, false)) {
      SCOPED_TRACE(file.string());
      const std::string c = loadOne(file);
      ++classes[c];
      ++tried;
      // Each .gltf there has a member of the wrong type, which is named (tinygltf would skip it).
      if (file.extension() == ".gltf") {
        EXPECT_EQ(c, "wrong type");
      }
    }
  }
  report("glTF2/wrongTypes + glTF2/SchemaFailures", tried, classes);
  EXPECT_GE(tried, 10u);
  EXPECT_GE(classes["wrong type"], 7);
}

struct KnownCase {
  const char* file;
  StatusCode code;        // Ok: loads
  const char* fragment;   // in the message
};

TEST(MalformedModels, KnownBrokenModelsGiveTheirErrors) {
  requireTestModels();
  const KnownCase cases[] = {
      {"glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", StatusCode::InvalidInput, ": vertex 0 has a non-finite coordinate (-inf, "},
      // assimp 5.2 said "Mesh "Mesh" has no faces", and dropped the bad triangle of the second silently.
      {"glTF2/IndexOutOfRange/AllIndicesOutOfRange.gltf", StatusCode::IoError,
       ": glTF: mesh 0 primitive 0: index 65535 (element 0 of accessor 0) is out of range: its POSITION, accessor 2, "
       "has 24 vertices"},
      {"glTF2/IndexOutOfRange/IndexOutOfRange.gltf", StatusCode::IoError,
       ": glTF: mesh 0 primitive 0: index 255 (element 0 of accessor 0) is out of range: its POSITION, accessor 2, "
       "has 24 vertices"},
      {"glTF2/MissingBin/BoxTextured.gltf", StatusCode::IoError,
       ": glTF: buffers[0].uri: could not open the referenced file \"BoxTextured0.bin\" (no such file)"},
      {"glTF2/RecursiveNodes/RecursiveNodes.gltf", StatusCode::IoError,
       ": glTF: nodes[0] is its own ancestor (the node hierarchy has a cycle)"},
      {"glTF2/TestNoRootNode/NoScene.gltf", StatusCode::IoError, ": glTF: there is no scene"},
      {"glTF2/TestNoRootNode/SceneWithoutNodes.gltf", StatusCode::InvalidInput, ": has no triangles"},
      {"glTF2/issue_3269/texcoord_crash.gltf", StatusCode::IoError,  // TEXCOORD_1 without TEXCOORD_0
       ": glTF: mesh 0 primitive 0: its TEXCOORD_n attributes are not numbered 0, 1, ... without gaps"},
      {"glTF2/wrongTypes/badArray.gltf", StatusCode::IoError,
       ": glTF: meshes[0].primitives is an object; glTF 2.0 requires an array"},
      {"glTF2/wrongTypes/badUint.gltf", StatusCode::IoError,
       ": glTF: materials[0].pbrMetallicRoughness.baseColorTexture.index is the number -1; glTF 2.0 requires a "
       "non-negative integer"},
      {"glTF2/draco/2CylinderEngine.gltf", StatusCode::IoError,
       ": glTF: mesh 0 primitive 0 is Draco-compressed (KHR_draco_mesh_compression), which is not supported"},
      // Its unused buffer views run past the buffer; the used ones are whole (assimp loaded it too).
      {"glTF2/IncorrectVertexArrays/Cube.gltf", StatusCode::Ok, ""},
      {"glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_00.gltf", StatusCode::InvalidInput, ": has no triangles"},  // points
      {"glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_02.gltf", StatusCode::IoError,
       ": glTF: mesh 0 primitive 0 is a line loop (mode 2)"},
      {"glTF/BoxTextured-glTF/BoxTextured.gltf", StatusCode::IoError,
       ": glTF 1.0 is not supported (glTF 2.0 only): asset.version is \"1.0\""},
      {"glTF/CesiumMilkTruck/CesiumMilkTruck.gltf", StatusCode::IoError,  // assimp 5.2: Member "version" was not of type "string"
       ": glTF 1.0 is not supported (glTF 2.0 only): asset.version is the number 1 (glTF 1.0 allowed a number; "
       "glTF 2.0 writes the string \"2.0\")"},
      {"glTF/BoxTextured-glTF-Binary/BoxTextured.glb", StatusCode::IoError,
       ": binary glTF: version 1 is not supported (glTF 2.0 only)"},
      {"invalid/malformed.obj", StatusCode::IoError, ": OBJ line 28: '0' is not a vertex reference (1, 2, ... or -1, -2, ...)"},
      {"invalid/malformed2.obj", StatusCode::Ok, ""},
      {"OBJ/number_formats.obj", StatusCode::IoError, ": OBJ line 11: '3.1+e2' is not a number"},  // assimp read 3.1
      {"invalid/empty.obj", StatusCode::IoError, ": is empty"},
      {"invalid/empty.ply", StatusCode::IoError, ": is empty"},
      {"invalid/OutOfMemory.off", StatusCode::UnsupportedFormat, ": unknown extension '.off'"},
      {"OBJ/testline.obj", StatusCode::InvalidInput, ": has no triangles"},
      {"PLY/points.ply", StatusCode::InvalidInput, ": has no triangles"},
      {"PLY/issue623.ply", StatusCode::IoError,
       ": PLY: element 'vertex' row 0, property 'vertex_indices': value 7.9417970000000002 is not a valid uchar"},
      {"PLY/pond.0.ply", StatusCode::IoError, ": PLY: element 'vertex' row 70048, property 'diffuse_red': the data ends early"},
  };
  for (const KnownCase& c : cases) {
    SCOPED_TRACE(c.file);
    const std::string path = (kAssimpModels / c.file).string();
    Scene scene;
    const Status s = loadScene(path, scene);
    EXPECT_EQ(s.code, c.code) << s.message;
    if (c.code == StatusCode::Ok) {
      EXPECT_TRUE(validateMesh(scene.mesh, path));
    } else {
      EXPECT_EQ(s.message.rfind(path + ": ", 0), 0u) << s.message;
      EXPECT_NE(s.message.find(c.fragment), std::string::npos) << s.message;
    }
  }
}

// Every .gltf, .glb, .obj and .ply the package ships (valid ones, odd ones, broken ones).
TEST(MalformedModels, EveryMeshFileInTheTestModelsLoadsOrIsRefused) {
  requireTestModels();
  std::map<std::string, int> classes;
  std::size_t tried = 0;
  for (const char* dir : {"glTF", "glTF2", "OBJ", "PLY", "invalid"}) {
    for (const fs::path& file : filesUnder(kAssimpModels / dir, true)) {
      SCOPED_TRACE(file.string());
      ++classes[loadOne(file)];
      ++tried;
    }
  }
  report("every .gltf/.glb/.obj/.ply in assimp-testmodels", tried, classes);
  EXPECT_GE(tried, 80u);
  EXPECT_GE(classes["loaded"], 40);
}

}  // namespace
}  // namespace sao::scenes
