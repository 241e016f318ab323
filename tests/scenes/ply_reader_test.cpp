// The PLY reader (samples/scenes/src/ply_reader.cpp, used for .ply instead of assimp's): the three
// encodings give the same mesh, extra elements and properties are skipped, and every malformed
// header or body is an error naming the problem (and, in the body, the element, row and property).
#include <algorithm>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "sao/scenes/mesh_file.h"
#include "test_models.h"

namespace sao::scenes {
namespace {

Status readPlyText(const std::string& bytes, Mesh& mesh) {
  return loadMeshFromMemory({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()}, "ply", "mem", mesh);
}

// A unit square (two triangles from one quad) at z = 1, with extras to skip: a normal and a colour
// per vertex, an "edge" element before the vertices, a texture-coordinate list on the faces.
const std::string kAsciiSquare =
    "ply\r\n"
    "format ascii 1.0\r\n"
    "comment a square\n"
    "obj_info anything\n"
    "Created by a program that writes free text here\n"
    "element edge 2\n"
    "property int vertex1\n"
    "property int vertex2\n"
    "element vertex 4\n"
    "property float nx\n"
    "property double x\n"
    "property float y\n"
    "property int z\n"
    "property uchar red\n"
    "element face 1\n"
    "property list uchar float texcoord\n"
    "property list uchar int vertex_indices\n"
    "end_header\n"
    "0 1\n1 2\n"
    "0 0 0 1 255\n0 1 0 1 255\n0 1 1 1 255\n0 0 1 1 255\n"
    "2 0.5 0.5 4 0 1 2 3\n";

void expectSquare(const Mesh& mesh) {
  ASSERT_EQ(mesh.positions.size(), 4u);
  EXPECT_EQ(mesh.positions[0], glm::vec3(0, 0, 1));
  EXPECT_EQ(mesh.positions[2], glm::vec3(1, 1, 1));
  ASSERT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
}

template <class T>
void put(std::string& out, T v, bool bigEndian) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (bigEndian) std::reverse(b, b + sizeof(T));
  out.append(b, sizeof(T));
}

// The square in binary: edges with a list (so skipped row by row), vertices as double x, float y,
// int z, faces with ushort counts and uint indices.
std::string binarySquare(bool bigEndian) {
  std::string s = std::string("ply\nformat ") + (bigEndian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\n"
                  "element edge 1\nproperty list uchar int vertices\n"
                  "element vertex 4\nproperty double x\nproperty float y\nproperty int z\n"
                  "element face 1\nproperty list ushort uint vertex_index\n"
                  "element pad 3\nproperty short p\n"
                  "end_header\n";
  put<std::uint8_t>(s, 2, bigEndian);
  put<std::int32_t>(s, 0, bigEndian);
  put<std::int32_t>(s, 1, bigEndian);
  const int xy[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (const auto& v : xy) {
    put<double>(s, v[0], bigEndian);
    put<float>(s, float(v[1]), bigEndian);
    put<std::int32_t>(s, 1, bigEndian);
  }
  put<std::uint16_t>(s, 4, bigEndian);
  for (std::uint32_t i : {0u, 1u, 2u, 3u}) put<std::uint32_t>(s, i, bigEndian);
  for (int i = 0; i < 3; ++i) put<std::int16_t>(s, std::int16_t(i), bigEndian);
  return s;
}

TEST(PlyReader, EveryEncodingGivesTheSameMesh) {
  Mesh ascii, little, big;
  Status s = readPlyText(kAsciiSquare, ascii);
  ASSERT_TRUE(s) << s.message;
  expectSquare(ascii);
  s = readPlyText(binarySquare(false), little);
  ASSERT_TRUE(s) << s.message;
  expectSquare(little);
  s = readPlyText(binarySquare(true), big);
  ASSERT_TRUE(s) << s.message;
  expectSquare(big);
}

TEST(PlyReader, ShortFacesAreLeftOutAndEmptyElementsCostNothing) {
  Mesh mesh;
  const Status s = readPlyText(
      "ply\nformat ascii 1.0\nelement nothing 18446744073709551615\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 3\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 1 0 0 0 1 0\n2 0 1\n0\n3 0 1 2\n",
      mesh);
  ASSERT_TRUE(s) << s.message;
  EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2}));
}

struct Bad {
  std::string bytes;
  StatusCode code;
  std::string message;  // after "mem: "
};

void PrintTo(const Bad& c, std::ostream* os) { *os << test::escapedText(c.bytes); }

class PlyReaderRejects : public ::testing::TestWithParam<Bad> {};

TEST_P(PlyReaderRejects, WithItsMessage) {
  Mesh mesh;
  mesh.positions = {{9, 9, 9}};
  const Status s = readPlyText(GetParam().bytes, mesh);
  EXPECT_EQ(s.code, GetParam().code);
  EXPECT_EQ(s.message, "mem: " + GetParam().message);
  EXPECT_EQ(mesh.positions.size(), 1u) << "the output changed on error";
}

const std::string kHead = "ply\nformat ascii 1.0\n";
const std::string kXyz = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
const std::string kFace = "element face 1\nproperty list uchar int vertex_indices\n";
const std::string kTriangle = "0 0 0 1 0 0 0 1 0\n";

std::string binaryHead(std::uint64_t vertices) {
  return "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
}

INSTANTIATE_TEST_SUITE_P(
    Cases, PlyReaderRejects,
    ::testing::Values(
        Bad{"PLY\n", StatusCode::IoError, "PLY: not a PLY file (the first line is not 'ply')"},
        Bad{"ply\nformat ascii 1.0\n", StatusCode::IoError, "PLY: the header has no end_header line"},
        Bad{"ply\n" + kXyz + "end_header\n", StatusCode::IoError, "PLY: the header has no format line"},
        Bad{"ply\nformat ascii 2.0\n", StatusCode::IoError,
            "PLY: header line 2: expected 'format ascii|binary_little_endian|binary_big_endian 1.0'"},
        Bad{"ply\nformat binary 1.0\n", StatusCode::IoError, "PLY: header line 2: unknown format 'binary'"},
        Bad{kHead + "format ascii 1.0\n", StatusCode::IoError, "PLY: header line 3: a second format line"},
        Bad{kHead + "element vertex -1\n", StatusCode::IoError, "PLY: header line 3: element count '-1' is not a number"},
        Bad{kHead + "element vertex\n", StatusCode::IoError, "PLY: header line 3: expected 'element NAME COUNT'"},
        Bad{kHead + "property float x\n", StatusCode::IoError, "PLY: header line 3: a property before any element"},
        Bad{kHead + "element vertex 1\nproperty flot x\n", StatusCode::IoError, "PLY: header line 4: unknown type 'flot'"},
        Bad{kHead + "element vertex 1\nproperty f\xb2\xb2loat x\n", StatusCode::IoError,
            "PLY: header line 4: unknown type 'f??loat'"},
        Bad{kHead + "element vertex 1\nproperty float\n", StatusCode::IoError,
            "PLY: header line 4: expected 'property TYPE NAME'"},
        Bad{kHead + kXyz + "element face 1\nproperty list float int vertex_indices\n", StatusCode::IoError,
            "PLY: header line 8: list count type 'float' is not an integer type"},
        Bad{kHead + kXyz + "element face 1\nproperty list uchar\n", StatusCode::IoError,
            "PLY: header line 8: expected 'property list COUNT_TYPE ITEM_TYPE NAME'"},
        Bad{kHead + "element point 1\nproperty float x\nend_header\n1\n", StatusCode::IoError, "PLY: no vertex element"},
        Bad{kHead + "element vertex 1\nproperty float x\nproperty float y\nend_header\n1 2\n", StatusCode::IoError,
            "PLY: the vertex element has no x, y and z properties"},
        Bad{binaryHead(4294967296ull), StatusCode::IoError,
            "PLY: the header declares 4294967296 vertices, more than 2^32 - 1"},
        Bad{kHead + kXyz + "end_header\n0 0 0 1 0 0\n", StatusCode::IoError,
            "PLY: element 'vertex' row 2, property 'x': the data ends early (after 6 values)"},
        Bad{kHead + kXyz + "end_header\n0 0 zero\n", StatusCode::IoError,
            "PLY: element 'vertex' row 0, property 'z': value 'zero' is not a valid float"},
        Bad{kHead + kXyz + kFace + "end_header\n" + kTriangle + "1.5 0 1 2\n", StatusCode::IoError,
            "PLY: element 'face' row 0, property 'vertex_indices': value 1.5 is not a valid uchar"},
        Bad{kHead + kXyz + kFace + "end_header\n" + kTriangle + "3 0 1 1e10\n", StatusCode::IoError,
            "PLY: element 'face' row 0, property 'vertex_indices': value 10000000000 is not a valid int"},
        Bad{kHead + kXyz + kFace + "end_header\n" + kTriangle + "255 0 1 2\n", StatusCode::IoError,
            "PLY: element 'face' row 0, property 'vertex_indices': the data ends early (after 13 values)"},
        Bad{kHead + kXyz + "element face 1\nproperty list char int vertex_indices\nend_header\n" + kTriangle + "-128 0 1 2\n",
            StatusCode::IoError, "PLY: element 'face' row 0, property 'vertex_indices': the list count -128 is negative"},
        Bad{kHead + kXyz + kFace + "end_header\n" + kTriangle + "3 0 -1 2\n", StatusCode::InvalidInput,
            "PLY: face 0 refers to vertex -1, but there are only 3 vertices"},
        Bad{kHead + kXyz + kFace + "end_header\n" + kTriangle + "3 0 1 3\n", StatusCode::InvalidInput,
            "PLY: face 0 refers to vertex 3, but there are only 3 vertices"},
        Bad{binaryHead(3) + std::string(35, '\0'), StatusCode::IoError,
            "PLY: element 'vertex' row 2, property 'z': the data ends early (after 8 values)"},
        Bad{"ply\nformat binary_little_endian 1.0\nelement junk 1000000000000\nproperty double d\n" + kXyz.substr(0, 0) +
                "end_header\n" + std::string(64, '\0'),
            StatusCode::IoError, "PLY: no vertex element"},
        Bad{"ply\nformat binary_little_endian 1.0\n" + kXyz + "element junk 1000000000000\nproperty double d\nend_header\n" +
                std::string(36 + 64, '\0'),
            StatusCode::IoError, "PLY: element 'junk': the data ends early"},
        Bad{kHead + kXyz + kFace + "end_header\n0 nan 0 1 0 0 0 1 0\n3 0 1 2\n", StatusCode::InvalidInput,
            "vertex 0 has a non-finite coordinate (0, nan, 0)"},
        Bad{kHead + kXyz + kFace + "end_header\n0 0 1e39 1 0 0 0 1 0\n3 0 1 2\n", StatusCode::InvalidInput,
            "vertex 0 has a non-finite coordinate (0, 0, inf)"},
        Bad{kHead + kXyz + kFace + "end_header\n" + kTriangle + "2 0 1\n", StatusCode::InvalidInput, "has no triangles"}));

}  // namespace
}  // namespace sao::scenes
