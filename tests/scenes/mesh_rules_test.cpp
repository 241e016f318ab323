// Input a user's tools write that the readers used to take silently wrong (docs/ROBUSTNESS.md
// section 4.8): a UTF-8 byte-order mark (OBJ lost its first vertex), glTF 1.0, glTF indices out
// of range and invalid byteStrides (assimp dropped triangles or read garbage; tinygltf reads an
// unparsable byteStride as packed), and degenerate
// triangles (an all-degenerate mesh rendered an empty image).
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sao/scenes/mesh_file.h"
#include "sao/scenes/scene.h"
#include "sao/scenes/scene_file.h"
#include "test_models.h"

namespace sao::scenes {
namespace {

using test::kAssimpModels;
using test::kCubeObj;
using test::TempDir;

const std::string kMark = "\xEF\xBB\xBF";

std::span<const std::uint8_t> bytes(std::string_view text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

std::string base64(std::string_view data) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < data.size(); i += 3) {
    std::uint32_t bits = std::uint32_t(std::uint8_t(data[i])) << 16;
    if (i + 1 < data.size()) bits |= std::uint32_t(std::uint8_t(data[i + 1])) << 8;
    if (i + 2 < data.size()) bits |= std::uint32_t(std::uint8_t(data[i + 2]));
    out += digits[bits >> 18 & 63];
    out += digits[bits >> 12 & 63];
    out += i + 1 < data.size() ? digits[bits >> 6 & 63] : '=';
    out += i + 2 < data.size() ? digits[bits & 63] : '=';
  }
  return out;
}

std::string le32(std::uint32_t v) {
  const char b[4] = {char(v), char(v >> 8), char(v >> 16), char(v >> 24)};
  return std::string(b, 4);
}

// A binary glTF of a JSON chunk and a BIN chunk (each padded to 4 bytes).
std::string glb(std::string json, std::string bin) {
  while (json.size() % 4) json += ' ';
  while (bin.size() % 4) bin += '\0';
  const std::string body = le32(std::uint32_t(json.size())) + "JSON" + json + le32(std::uint32_t(bin.size())) +
                           std::string("BIN\0", 4) + bin;
  return "glTF" + le32(2) + le32(std::uint32_t(12 + body.size())) + body;
}

// One indexed mesh primitive: the positions (xyz each) at `stride` bytes apart (0: no byteStride,
// packed), then the uint16 indices. `viewShortBy` shortens the vertex buffer view's byteLength.
// A strided view holds count * stride bytes (as assimp 5.2, the reader before tinygltf, wanted),
// though glTF 2.0 lets the last element end the view.
struct Primitive {
  std::vector<float> positions;
  std::vector<std::uint16_t> indices;
  double stride = 0;
  std::uint32_t viewShortBy = 0;

  std::uint32_t vertexBytes() const {
    const auto count = std::uint32_t(positions.size() / 3);
    return stride > 12 ? std::uint32_t(stride) * count : 12 * count;
  }
  std::string bin() const {
    const std::uint32_t step = stride >= 4 ? std::uint32_t(stride) : 12;
    std::string out(vertexBytes(), '\0');
    for (std::size_t v = 0; v < positions.size() / 3 && v * step + 12 <= out.size(); ++v)
      std::memcpy(out.data() + v * step, &positions[3 * v], 12);
    while (out.size() % 4) out += '\0';
    out.append(reinterpret_cast<const char*>(indices.data()), indices.size() * 2);
    return out;
  }
  // The JSON with the buffer at `uri` ("" for a .glb's BIN chunk).
  std::string json(const std::string& uri) const {
    const std::uint32_t indexOffset = (vertexBytes() + 3) / 4 * 4;
    char strideText[64] = "";
    if (stride != 0) std::snprintf(strideText, sizeof strideText, ", \"byteStride\": %g", stride);
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "buffers": [{"byteLength": )" + std::to_string(bin().size()) +
           (uri.empty() ? "" : ", \"uri\": \"" + uri + "\"") + R"(}],
  "bufferViews": [{"buffer": 0, "byteLength": )" + std::to_string(vertexBytes() - viewShortBy) + strideText + R"(},
                  {"buffer": 0, "byteOffset": )" + std::to_string(indexOffset) + R"(, "byteLength": )" +
           std::to_string(indices.size() * 2) + R"(}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": )" + std::to_string(positions.size() / 3) +
           R"(, "type": "VEC3"},
                {"bufferView": 1, "componentType": 5123, "count": )" + std::to_string(indices.size()) +
           R"(, "type": "SCALAR"}]})";
  }
  std::string dataUriGltf() const { return json("data:application/octet-stream;base64," + base64(bin())); }
};

// A quad of two triangles, 4 vertices.
Primitive quad() { return {{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, {0, 1, 2, 0, 2, 3}}; }

// The primitive as a .gltf with a data URI, from memory and from a file; as a .gltf with a .bin
// next to it; and as a .glb: each gives `message` after the file's name (or loads when empty).
void expectEveryWay(const Primitive& p, const std::string& message, std::size_t triangles = 0) {
  TempDir dir;
  dir.write("quad.bin", p.bin());
  const std::vector<std::pair<std::string, std::string>> files = {
      {dir.write("uri.gltf", p.dataUriGltf()), ""},
      {dir.write("external.gltf", p.json("quad.bin")), ""},
      {dir.write("binary.glb", glb(p.json(""), p.bin())), ""},
      {"mem", p.dataUriGltf()}};
  for (const auto& [name, text] : files) {
    SCOPED_TRACE(name);
    Mesh mesh;
    const Status s = text.empty() ? loadMeshFile(name, mesh) : loadMeshFromMemory(bytes(text), "gltf", name, mesh);
    if (message.empty()) {
      ASSERT_TRUE(s) << s.message;
      EXPECT_EQ(mesh.triangleCount(), triangles);
    } else {
      EXPECT_EQ(s.code, StatusCode::IoError);
      EXPECT_EQ(s.message, name + ": " + message);
      EXPECT_TRUE(mesh.positions.empty());
    }
  }
}

// ---- UTF-8 byte-order mark

TEST(ByteOrderMark, ObjKeepsItsFirstVertexAndIndices) {
  TempDir dir;
  for (int fromFile = 0; fromFile < 2; ++fromFile) {
    Mesh plain, marked;
    const std::string withMark = kMark + std::string(kCubeObj);
    const Status a = fromFile ? loadMeshFile(dir.write("plain.obj", kCubeObj), plain)
                              : loadMeshFromMemory(bytes(kCubeObj), "obj", "plain", plain);
    const Status b = fromFile ? loadMeshFile(dir.write("marked.obj", withMark), marked)
                              : loadMeshFromMemory(bytes(withMark), "obj", "marked", marked);
    ASSERT_TRUE(a) << a.message;
    ASSERT_TRUE(b) << b.message;
    EXPECT_EQ(marked.positions, plain.positions);  // 8, the first (0, 0, 0) included
    EXPECT_EQ(marked.indices, plain.indices);
    EXPECT_EQ(marked.positions.size(), 8u);
  }
  // The mark before a vertex on line 1: a line error still names line 1.
  Mesh mesh;
  const std::string bad = kMark + "v 1 x 2\n";
  EXPECT_EQ(loadMeshFromMemory(bytes(bad), "obj", "mem", mesh).message, "mem: OBJ line 1: 'x' is not a number");
}

TEST(ByteOrderMark, SceneFileIsAccepted) {
  TempDir dir;
  dir.write("cube.obj", kCubeObj);
  const std::string path =
      dir.write("marked.scene", kMark + "mesh cube.obj\nview front eye 0.5 0.5 4 target 0.5 0.5 0\n");
  Scene scene;
  const Status s = loadScene(path, scene);
  ASSERT_TRUE(s) << s.message;
  EXPECT_EQ(scene.mesh.triangleCount(), 12u);
  ASSERT_EQ(scene.views.size(), 1u);
  EXPECT_EQ(scene.views[0].name, "front");
  // A mark anywhere else is still an unknown word.
  SceneFile file;
  const Status late = parseSceneFile("mesh cube.obj\n" + kMark + "view x eye 0 0 1 target 0 0 0\n", "s.scene", file);
  EXPECT_EQ(late.message.rfind("s.scene:2: unknown keyword '???view' (expected ", 0), 0u) << late.message;
}

TEST(ByteOrderMark, PlyIsRefusedWithTheReason) {
  const std::string ply =
      kMark +
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  Mesh mesh;
  const Status s = loadMeshFromMemory(bytes(ply), "ply", "mem", mesh);
  EXPECT_EQ(s.code, StatusCode::IoError);
  EXPECT_EQ(s.message,
            "mem: PLY: starts with a UTF-8 byte-order mark before 'ply'; save it without the mark (as plain ASCII)");
  ASSERT_TRUE(loadMeshFromMemory(bytes(ply.substr(3)), "ply", "mem", mesh));  // the same file without it loads
}

TEST(ByteOrderMark, GltfIsAcceptedButNotInsideABinaryGltf) {
  TempDir dir;
  const Primitive p = quad();
  dir.write("quad.bin", p.bin());
  Mesh plain;
  ASSERT_TRUE(loadMeshFile(dir.write("plain.gltf", p.json("quad.bin")), plain));
  // assimp 5.2, the reader before tinygltf, said "JSON parse error, offset 0: Invalid value."
  for (const std::string& text : {p.json("quad.bin"), p.dataUriGltf()}) {
    Mesh fromFile, fromMemory;
    const Status f = loadMeshFile(dir.write("marked.gltf", kMark + text), fromFile);
    ASSERT_TRUE(f) << f.message;
    EXPECT_EQ(fromFile.positions, plain.positions);
    EXPECT_EQ(fromFile.indices, plain.indices);
    if (text.find("data:") != std::string::npos) {
      const std::string marked = kMark + text;
      const Status m = loadMeshFromMemory(bytes(marked), "gltf", "mem", fromMemory);
      ASSERT_TRUE(m) << m.message;
      EXPECT_EQ(fromMemory.positions, plain.positions);
    }
  }
  Mesh mesh;
  const std::string binary = dir.write("marked.glb", glb(kMark + p.json(""), p.bin()));
  const Status s = loadMeshFile(binary, mesh);
  EXPECT_EQ(s.message, binary + ": binary glTF: the JSON chunk starts with a UTF-8 byte-order mark, which glTF 2.0 "
                                "forbids there; write the chunk without it");
}

// ---- glTF 1.0

TEST(GltfVersion, GltfOneIsNamedAsUnsupported) {
  const Primitive p = quad();
  const std::string good = p.dataUriGltf();
  const std::string asset = R"("asset": {"version": "2.0"}, )";
  ASSERT_NE(good.find(asset), std::string::npos);
  struct Case {
    std::string replacement, message;
  };
  const Case cases[] = {
      {R"("asset": {"version": "1.0"}, )", "glTF 1.0 is not supported (glTF 2.0 only): asset.version is \"1.0\""},
      {R"("asset": {"version": 1}, )",
       "glTF 1.0 is not supported (glTF 2.0 only): asset.version is the number 1 (glTF 1.0 allowed a number; glTF 2.0 "
       "writes the string \"2.0\")"},
      {"", "glTF 1.0 is not supported (glTF 2.0 only): there is no \"asset\", which glTF 2.0 requires"},
      {R"("asset": {"generator": "x"}, )",
       "glTF 1.0 is not supported (glTF 2.0 only): \"asset\" has no \"version\", which glTF 2.0 requires"},
      {R"("asset": {"version": "3.0"}, )", "glTF: asset.version \"3.0\" is not supported (glTF 2.0 only)"},
  };
  for (const Case& c : cases) {
    std::string text = good;
    text.replace(text.find(asset), asset.size(), c.replacement);
    Mesh mesh;
    const Status s = loadMeshFromMemory(bytes(text), "gltf", "mem", mesh);
    EXPECT_EQ(s.code, StatusCode::IoError);
    EXPECT_EQ(s.message, "mem: " + c.message);
  }
  std::string minor = good;
  minor.replace(minor.find(asset), asset.size(), R"("asset": {"version": "2.1"}, )");
  Mesh mesh;
  EXPECT_TRUE(loadMeshFromMemory(bytes(minor), "gltf", "mem", mesh));  // a later 2.x stays readable
}

// ---- glTF indices and strides

TEST(GltfAccessors, AValidQuadLoadsEveryWay) {
  expectEveryWay(quad(), "", 2);
  Primitive padded = quad();
  padded.stride = 16;  // 4 bytes of padding after each position
  expectEveryWay(padded, "", 2);
  Mesh mesh;
  const std::string text = padded.dataUriGltf();
  ASSERT_TRUE(loadMeshFromMemory(bytes(text), "gltf", "mem", mesh));
  Mesh packed;
  const std::string packedText = quad().dataUriGltf();
  ASSERT_TRUE(loadMeshFromMemory(bytes(packedText), "gltf", "mem", packed));
  EXPECT_EQ(mesh.positions, packed.positions);
}

TEST(GltfAccessors, AnIndexOutOfRangeIsNamed) {
  Primitive p = quad();
  p.indices[4] = 7;  // assimp dropped that triangle without a word ("has no faces" when all were)
  expectEveryWay(p, "glTF: mesh 0 primitive 0: index 7 (element 4 of accessor 1) is out of range: its POSITION, "
                    "accessor 0, has 4 vertices");
  p.indices = {4, 4, 4};
  expectEveryWay(p, "glTF: mesh 0 primitive 0: index 4 (element 0 of accessor 1) is out of range: its POSITION, "
                    "accessor 0, has 4 vertices");
  // Indices at byte 64 of the buffer, which is not on a 3-byte (4-character) group of the data URI.
  p = quad();
  p.stride = 16;
  p.indices[5] = 9;
  expectEveryWay(p, "glTF: mesh 0 primitive 0: index 9 (element 5 of accessor 1) is out of range: its POSITION, "
                    "accessor 0, has 4 vertices");
}

TEST(GltfAccessors, AnInvalidByteStrideIsRefused) {
  const std::string element = "glTF: accessor 0 (VEC3 of componentType 5126, 12 bytes an element): ";
  const std::string rule = "; glTF 2.0 requires a multiple of 4 from 4 to 252";
  struct Case {
    double stride;
    std::uint32_t shortBy;
    std::string message;
  };
  const Case cases[] = {
      {14, 0, element + "its bufferView 0 has byteStride 14" + rule},
      {2, 0, element + "its bufferView 0 has byteStride 2" + rule},
      {0.5, 0, element + "its bufferView 0 has byteStride 0.5" + rule},
      {-12, 0, element + "its bufferView 0 has byteStride -12" + rule},
      {256, 0, element + "its bufferView 0 has byteStride 256" + rule},
      {8, 0, element + "the byteStride 8 of its bufferView 0 is smaller than an element, so elements would overlap"},
      {16, 8,
       element + "4 elements from byteOffset 0 with a stride of 16 run past the byteLength 56 of its bufferView 0"},
      {0, 1,
       element + "4 elements from byteOffset 0 with a stride of 12 run past the byteLength 47 of its bufferView 0"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.stride);
    Primitive p = quad();
    p.stride = c.stride;
    p.viewShortBy = c.shortBy;
    expectEveryWay(p, c.message);
  }
}

TEST(GltfAccessors, ABufferViewPastItsBufferIsRefused) {
  Primitive p = quad();
  const std::string length = "\"byteLength\": " + std::to_string(p.bin().size()) + ",";
  // A buffer of 40 bytes, its data URI holding just those.
  std::string text = p.json("data:application/octet-stream;base64," + base64(p.bin().substr(0, 40)));
  ASSERT_NE(text.find(length), std::string::npos);
  text.replace(text.find(length), length.size(), "\"byteLength\": 40,");
  Mesh mesh;
  Status s = loadMeshFromMemory(bytes(text), "gltf", "mem", mesh);
  EXPECT_EQ(s.message, "mem: glTF: bufferView 0 (byteOffset 0, byteLength 48) runs past the byteLength 40 of buffer 0");
  // byteLength 40 over a data URI of more bytes: refused, with the sizes (assimp 5.2 threw on the
  // mismatch without freeing what it decoded, a leak found by fuzzing).
  text = p.dataUriGltf();
  text.replace(text.find(length), length.size(), "\"byteLength\": 40,");
  s = loadMeshFromMemory(bytes(text), "gltf", "mem", mesh);
  EXPECT_EQ(s.message, "mem: glTF: buffers[0].uri: the data holds " + std::to_string(p.bin().size()) +
                           " bytes, but byteLength is 40");
}

// A buffer's data URI: glTF 2.0's media types only, base64 only, valid base64.
TEST(GltfAccessors, ABufferDataUriOfAnotherKindIsRefused) {
  const Primitive p = quad();
  const std::string data = base64(p.bin());
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"data:~application/octet-stream;base64," + data,
       "a data URI 'data:~application/octet-stream;base64' is not of glTF 2.0's buffer media types "
       "(application/octet-stream, application/gltf-buffer)"},
      {"data:application/octet-stream," + data, "the data URI is not base64 (its header does not end in ;base64)"},
      {"data:application/octet-stream;base64," + data.substr(0, 8) + "\u023e" + data.substr(8),
       "the data is not valid base64 (a character outside the alphabet, misplaced '=', or a length that is no "
       "multiple of 4)"},
  };
  for (const auto& [uri, message] : cases) {
    SCOPED_TRACE(uri.substr(0, 48));
    Mesh mesh;
    const Status s = loadMeshFromMemory(bytes(p.json(uri)), "gltf", "mem", mesh);
    EXPECT_EQ(s.code, StatusCode::IoError);
    EXPECT_EQ(s.message, "mem: glTF: buffers[0].uri: " + message);
  }
  Mesh mesh;
  EXPECT_TRUE(loadMeshFromMemory(bytes(p.json("data:application/gltf-buffer;base64," + data)), "gltf", "mem", mesh));
}

// ---- glTF node trees, strips, fans and sparse positions (read from tinygltf's model)

// Four positions of a unit quad at z = 0 (48 bytes), then a sparse replacement of vertex 2 by
// (2, 2, 0): its index (uint16, padded to 4 bytes) and its value.
std::string quadWithSparse(const std::string& primitives, const std::string& nodes, const std::string& scene) {
  const float quad[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const float moved[3] = {2, 2, 0};
  std::string bin(reinterpret_cast<const char*>(quad), 48);
  bin += std::string("\x02\x00\x00\x00", 4) + std::string(reinterpret_cast<const char*>(moved), 12);
  return R"({"asset": {"version": "2.0"}, )" + scene + R"(, "nodes": )" + nodes + R"(,
  "meshes": [{"primitives": )" + primitives + R"(}],
  "buffers": [{"byteLength": 64, "uri": "data:application/octet-stream;base64,)" + base64(bin) + R"("}],
  "bufferViews": [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 2},
                  {"buffer": 0, "byteOffset": 52, "byteLength": 12}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
                {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                 "sparse": {"count": 1, "indices": {"bufferView": 1, "componentType": 5123},
                            "values": {"bufferView": 2}}}]})";
}

TEST(GltfModel, StripsFansSparsePositionsAndNodeTrees) {
  const std::string oneNode = R"([{"mesh": 0}])", oneScene = R"("scenes": [{"nodes": [0]}])";
  Mesh mesh;
  // A strip and a fan of the same 4 vertices: 2 triangles each, 4 vertices in all per primitive.
  Status s = loadMeshFromMemory(bytes(quadWithSparse(R"([{"attributes": {"POSITION": 0}, "mode": 5},
      {"attributes": {"POSITION": 0}, "mode": 6}])", oneNode, oneScene)), "gltf", "mem", mesh);
  ASSERT_TRUE(s) << s.message;
  EXPECT_EQ(mesh.triangleCount(), 4u);
  EXPECT_EQ(mesh.positions.size(), 8u);
  EXPECT_EQ(std::vector<std::uint32_t>(mesh.indices.begin(), mesh.indices.begin() + 6),
            (std::vector<std::uint32_t>{0, 1, 2, 1, 3, 2}));  // the strip's second triangle turned
  EXPECT_EQ(std::vector<std::uint32_t>(mesh.indices.begin() + 6, mesh.indices.end()),
            (std::vector<std::uint32_t>{5, 6, 4, 6, 7, 4}));  // the fan around its first vertex
  // Sparse positions: vertex 2 is (2, 2, 0); a child node inherits its parent's transform.
  const std::string tree = R"([{"children": [1], "translation": [10, 0, 0]}, {"mesh": 0, "scale": [2, 2, 2]}])";
  s = loadMeshFromMemory(bytes(quadWithSparse(R"([{"attributes": {"POSITION": 1}}])", tree, oneScene)), "gltf", "mem",
                         mesh);
  ASSERT_TRUE(s) << s.message;
  EXPECT_EQ(mesh.triangleCount(), 1u);  // 4 vertices make 1 triangle in mode 4
  ASSERT_EQ(mesh.positions.size(), 4u);
  EXPECT_EQ(mesh.positions[2], glm::vec3(14, 4, 0));
  // Two scenes: "scene" picks the second, which has the mesh twice through two nodes.
  s = loadMeshFromMemory(bytes(quadWithSparse(R"([{"attributes": {"POSITION": 0}, "mode": 6}])",
                                              R"([{"mesh": 0}, {"mesh": 0, "translation": [0, 0, 5]}])",
                                              R"("scene": 1, "scenes": [{"nodes": []}, {"nodes": [0, 1]}])")),
                         "gltf", "mem", mesh);
  ASSERT_TRUE(s) << s.message;
  EXPECT_EQ(mesh.triangleCount(), 4u);

  struct Case {
    std::string nodes, scene, message;
  };
  const Case cases[] = {
      {R"([{"children": [1]}, {"children": [0], "mesh": 0}])", oneScene,
       "glTF: nodes[0] is its own ancestor (the node hierarchy has a cycle)"},
      {R"([{"children": [2]}, {"children": [2]}, {"mesh": 0}])", R"("scenes": [{"nodes": [0, 1]}])",
       "glTF: node 2 is a child of node 0 and of node 1; glTF 2.0 allows one parent"},
      {R"([{"children": [1]}, {"mesh": 0}])", R"("scenes": [{"nodes": [1]}])",
       "glTF: scenes[0].nodes names node 1, which is a child of node 0; a scene lists root nodes only"},
      {oneNode, R"("scenes": [{"nodes": [0, 0]}])", "glTF: scenes[0].nodes names node 0 twice"},
      {R"([{"mesh": 3}])", oneScene, "glTF: nodes[0].mesh is 3, which does not exist"},
      {R"([{"mesh": 0, "rotation": [0, 0, 1]}])", oneScene, "glTF: nodes[0].rotation has 3 numbers; glTF 2.0 requires 4"},
      {oneNode, R"("scene": 2, "scenes": [{"nodes": [0]}])", "glTF: \"scene\" is 2, which does not exist"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.message);
    Mesh untouched;
    s = loadMeshFromMemory(bytes(quadWithSparse(R"([{"attributes": {"POSITION": 0}}])", c.nodes, c.scene)), "gltf",
                           "mem", untouched);
    EXPECT_EQ(s.code, StatusCode::IoError);
    EXPECT_EQ(s.message, "mem: " + c.message);
    EXPECT_TRUE(untouched.positions.empty());
  }
}

// ---- degenerate triangles

TEST(DegenerateTriangles, TheThresholdIsAMillionthOfTheLongestEdge) {
  EXPECT_TRUE(isDegenerateTriangle({0, 0, 0}, {1, 1, 1}, {2, 2, 2}));    // collinear
  EXPECT_TRUE(isDegenerateTriangle({0, 0, 0}, {0, 0, 0}, {0, 1, 0}));    // a repeated corner
  EXPECT_TRUE(isDegenerateTriangle({5, 5, 5}, {5, 5, 5}, {5, 5, 5}));    // a point
  EXPECT_TRUE(isDegenerateTriangle({0, 0, 0}, {1, 0, 0}, {0.5f, 5e-7f, 0}));
  EXPECT_FALSE(isDegenerateTriangle({0, 0, 0}, {1, 0, 0}, {0.5f, 2e-6f, 0}));
  EXPECT_FALSE(isDegenerateTriangle({0, 0, 0}, {1e-6f, 0, 0}, {0, 1e-6f, 0}));  // tiny but not thin
}

TEST(DegenerateTriangles, AMeshOfOnlyDegenerateTrianglesIsRefused) {
  const std::string obj = "v 0 0 0\nv 1 1 1\nv 2 2 2\nv 3 3 3\nf 1 2 3\nf 2 3 4\nf 1 1 4\n";
  Mesh mesh;
  const Status s = loadMeshFromMemory(bytes(obj), "obj", "mem", mesh);
  EXPECT_EQ(s.code, StatusCode::InvalidInput);
  EXPECT_EQ(s.message, "mem: all its 3 triangles are degenerate (no area: corners repeated or on one line), so "
                       "nothing would be drawn");
  EXPECT_TRUE(mesh.positions.empty());
  // The same through a glTF: three collinear vertices.
  Primitive p{{0, 0, 0, 1, 0, 0, 2, 0, 0}, {0, 1, 2}};
  const std::string text = p.dataUriGltf();
  EXPECT_EQ(loadMeshFromMemory(bytes(text), "gltf", "gltf", mesh).message,
            "gltf: all its 1 triangles are degenerate (no area: corners repeated or on one line), so nothing would be "
            "drawn");
}

TEST(DegenerateTriangles, SomeAreLeftOutWithAWarning) {
  TempDir dir;
  const std::string path = dir.write("cube.obj", std::string(kCubeObj) + "f 1 2 2\nf 1 2 1\n");
  Scene scene;
  ASSERT_TRUE(loadScene(path, scene));
  EXPECT_EQ(scene.mesh.triangleCount(), 12u);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_EQ(scene.warnings[0], path + ": 2 of 14 triangles are degenerate (no area: corners repeated or on one line) "
                                      "and were left out");
  for (std::size_t t = 0; t < scene.mesh.triangleCount(); ++t) {
    const auto& p = scene.mesh.positions;
    const auto& i = scene.mesh.indices;
    EXPECT_FALSE(isDegenerateTriangle(p[i[3 * t]], p[i[3 * t + 1]], p[i[3 * t + 2]])) << t;
  }
  // In a scene file, the warning names the scene's line and the mesh.
  const std::string scenePath = dir.write("two.scene", "mesh cube.obj\nmesh cube.obj\ntransform translate 3 0 0\n");
  Scene two;
  ASSERT_TRUE(loadScene(scenePath, two));
  EXPECT_EQ(two.mesh.triangleCount(), 24u);
  ASSERT_EQ(two.warnings.size(), 2u);
  EXPECT_EQ(two.warnings[1], scenePath + ":2: " + path +
                                 ": 2 of 14 triangles are degenerate (no area: corners repeated or on one line) and "
                                 "were left out");
  // A clean mesh: no warning.
  Scene clean;
  ASSERT_TRUE(loadScene(dir.write("clean.obj", kCubeObj), clean));
  EXPECT_TRUE(clean.warnings.empty());
}

TEST(DegenerateTriangles, ValidateMeshRefusesOnlyDegenerateTriangles) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}};
  m.indices = {0, 1, 2};
  EXPECT_EQ(validateMesh(m, "m").message,
            "m: all its 1 triangles are degenerate (no area: corners repeated or on one line), so nothing would be "
            "drawn");
  m.indices = {0, 1, 2, 0, 1, 3};
  EXPECT_TRUE(validateMesh(m, "m"));
}

// ---- the real glTF 1.0 model and out-of-range models of assimp-testmodels

TEST(GltfVersion, CesiumMilkTruckIsNamedAsGltfOne) {
  const auto path = kAssimpModels / "glTF/CesiumMilkTruck/CesiumMilkTruck.gltf";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is missing: install assimp-testmodels";
  Mesh mesh;
  // assimp 5.2 said: Member "version" was not of type "string"; tinygltf would read it as glTF 2.0.
  EXPECT_EQ(loadMeshFile(path.string(), mesh).message,
            path.string() + ": glTF 1.0 is not supported (glTF 2.0 only): asset.version is the number 1 (glTF 1.0 "
                            "allowed a number; glTF 2.0 writes the string \"2.0\")");
}

}  // namespace
}  // namespace sao::scenes
