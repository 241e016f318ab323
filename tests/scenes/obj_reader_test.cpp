// The OBJ reader (samples/scenes/src/obj_reader.cpp, used for .obj instead of assimp's): the
// reference forms, negative and forward references, continuation lines, what is skipped, and
// every malformed line with its message.
#include <string>

#include <gtest/gtest.h>

#include "sao/scenes/mesh_file.h"
#include "test_models.h"

namespace sao::scenes {
namespace {

Status readObjText(const std::string& text, Mesh& mesh) {
  return loadMeshFromMemory({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}, "obj", "mem", mesh);
}

TEST(ObjReader, ReferenceFormsAndStatements) {
  Mesh mesh;
  const Status s = readObjText(
      "# a quad and a triangle\r\n"
      "mtllib nowhere.mtl\r\n"
      "o thing\ng group\ns off\nusemtl red\n"
      "v 0 0 0\nv 1 0 0 1.0\nv +1 1 0 0.5 0.5 0.5\nv 0 1e0 \\\n 0\n"  // w, colours, a continuation
      "vt 0 0\nvn 0 0 1\nvp 0.5\n"
      "f 1/1/1 2/1/1 3//1 4\n"        // a quad: two triangles
      "f -4 -3 -2\n"                  // negative: relative to the 4 vertices so far
      "l 1 2\np 3\nf 1 2\n"           // a line, a point, a face of two vertices: left out
      "f 5 1 2\n"                     // a forward reference, to the vertex after it
      "v 0 0 1\n",
      mesh);
  ASSERT_TRUE(s) << s.message;
  ASSERT_EQ(mesh.positions.size(), 5u);
  EXPECT_EQ(mesh.positions[2], glm::vec3(1, 1, 0));
  EXPECT_EQ(mesh.positions[3], glm::vec3(0, 1, 0));
  EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 0, 1, 2, 4, 0, 1}));
}

TEST(ObjReader, OutOfRangeNumbersBecomeInfinityOrZero) {
  Mesh mesh;
  Status s = readObjText("v 1e-400 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", mesh);
  ASSERT_TRUE(s) << s.message;
  EXPECT_EQ(mesh.positions[0].x, 0.0f);
  s = readObjText("v 1e400 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", mesh);
  EXPECT_EQ(s.message, "mem: vertex 0 has a non-finite coordinate (inf, 0, 0)");
}

struct Bad {
  std::string text;
  StatusCode code;
  std::string message;  // after "mem: "
};

void PrintTo(const Bad& c, std::ostream* os) { *os << test::escapedText(c.text); }

class ObjReaderRejects : public ::testing::TestWithParam<Bad> {};

TEST_P(ObjReaderRejects, WithItsMessage) {
  Mesh mesh;
  mesh.positions = {{9, 9, 9}};
  const Status s = readObjText(GetParam().text, mesh);
  EXPECT_EQ(s.code, GetParam().code);
  EXPECT_EQ(s.message, "mem: " + GetParam().message);
  EXPECT_EQ(mesh.positions.size(), 1u) << "the output changed on error";
}

const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

INSTANTIATE_TEST_SUITE_P(
    Cases, ObjReaderRejects,
    ::testing::Values(
        Bad{"v 1 2\n", StatusCode::IoError, "OBJ line 1: a vertex needs 3 coordinates, got 2"},
        Bad{"# x\nv 1 2 three\n", StatusCode::IoError, "OBJ line 2: 'three' is not a number"},
        Bad{"v 1 2 3.1+e2\n", StatusCode::IoError, "OBJ line 1: '3.1+e2' is not a number"},
        Bad{"v 1 2 \x86\x01\n", StatusCode::IoError, "OBJ line 1: '?\?' is not a number"},
        Bad{kTriangle + "f 1 2 0\n", StatusCode::IoError, "OBJ line 4: '0' is not a vertex reference (1, 2, ... or -1, -2, ...)"},
        Bad{kTriangle + "f 1 2 x/1\n", StatusCode::IoError, "OBJ line 4: 'x/1' is not a vertex reference (1, 2, ... or -1, -2, ...)"},
        Bad{kTriangle + "f 1 2 3.0\n", StatusCode::IoError, "OBJ line 4: '3.0' is not a vertex reference (1, 2, ... or -1, -2, ...)"},
        Bad{kTriangle + "f 1 2 99999999999999999999\n", StatusCode::IoError,
            "OBJ line 4: '99999999999999999999' is not a vertex reference (1, 2, ... or -1, -2, ...)"},
        Bad{kTriangle + "f 1 2 -4\n", StatusCode::InvalidInput, "OBJ line 4: vertex -4 is before the first of the 3 vertices so far"},
        Bad{kTriangle + "f 1 2 4294967297\n", StatusCode::InvalidInput, "OBJ line 4: vertex 4294967297 is beyond 2^32 - 1"},
        Bad{kTriangle + "f 1 2 \\\n  5\nv 1 1 1\n", StatusCode::InvalidInput,
            "OBJ line 4: a face refers to vertex 5, but there are only 4 vertices"},
        Bad{"v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", StatusCode::InvalidInput, "vertex 0 has a non-finite coordinate (nan, 0, 0)"},
        Bad{kTriangle + "l 1 2 3\np 1\n", StatusCode::InvalidInput, "has no triangles"},
        Bad{"v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n", StatusCode::InvalidInput, "all its triangles are at one point (1, 1, 1)"}));

}  // namespace
}  // namespace sao::scenes
