// A parsed glTF's triangles: the default scene's node trees walked from their roots, each mesh's
// triangle primitives read from their accessors (bounds-checked here again: tinygltf checks none
// of them), transformed and appended.
#include "gltf_mesh.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <unordered_map>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "file_checks.h"
#include "sao/scenes/mesh_file.h"

namespace sao::scenes::detail {

namespace {

using tinygltf::Accessor;
using tinygltf::Model;

// Elements of an accessor without a buffer view (zeros, then its sparse values): at most this many,
// so that a few bytes of JSON cannot ask for gigabytes.
constexpr std::size_t kMaxZeroFilledElements = std::size_t(1) << 24;

template <class T>
const T* item(const std::vector<T>& list, int i) {
  return i >= 0 && std::size_t(i) < list.size() ? &list[std::size_t(i)] : nullptr;
}

std::uint32_t readUnsigned(const unsigned char* p, std::size_t size) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < size; ++i) v |= std::uint32_t(p[i]) << (8 * i);  // little-endian
  return v;
}

std::size_t indexSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return 4;
    default: return 0;
  }
}

// A position's bits, -0 as +0: equal keys are equal positions.
struct Key {
  float x, y, z;
  bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct KeyHash {
  std::size_t operator()(const Key& k) const {
    std::uint32_t b[3];
    std::memcpy(b, &k, sizeof b);
    return std::hash<std::uint64_t>()((std::uint64_t(b[0]) << 32 | b[1]) ^ (std::uint64_t(b[2]) * 0x9E3779B97F4A7C15ull));
  }
};

class Reader {
 public:
  Reader(const Model& model, std::string_view name) : model_(model), name_(name) {}

  Status error(const std::string& problem) const { return fileError(StatusCode::IoError, name_, "glTF: " + problem); }
  std::string_view name() const { return name_; }

  // The elements of accessor `a`, `elementSize` bytes each, packed, its sparse values applied.
  Status elements(int a, std::size_t elementSize, std::vector<unsigned char>& out) const {
    const Accessor& accessor = model_.accessors[std::size_t(a)];
    const std::string what = "accessor " + std::to_string(a);
    if (accessor.bufferView < 0) {
      if (!accessor.sparse.isSparse)
        return error(what + " has neither a bufferView nor sparse values: no data to read");
      if (accessor.count > kMaxZeroFilledElements)
        return error(what + " has " + std::to_string(accessor.count) + " elements without a bufferView, more than " +
                     std::to_string(kMaxZeroFilledElements));
      out.assign(accessor.count * elementSize, 0);
    } else {
      const unsigned char* first = nullptr;
      std::size_t stride = 0;
      if (Status s = span(accessor.bufferView, accessor.byteOffset, accessor.count, elementSize, true, what, first, stride); !s)
        return s;
      out.resize(accessor.count * elementSize);
      for (std::size_t i = 0; i < accessor.count; ++i) std::memcpy(&out[i * elementSize], first + i * stride, elementSize);
    }
    return accessor.sparse.isSparse ? applySparse(accessor, what, elementSize, out) : Status::success();
  }

 private:
  const Model& model_;
  std::string_view name_;

  // Where `count` elements of `elementSize` bytes start, `byteOffset` into buffer view `v`.
  Status span(int v, std::int64_t byteOffset, std::size_t count, std::size_t elementSize, bool strided,
              const std::string& what, const unsigned char*& first, std::size_t& stride) const {
    const tinygltf::BufferView* view = item(model_.bufferViews, v);
    if (view == nullptr) return error(what + " refers to bufferView " + std::to_string(v) + ", which does not exist");
    const tinygltf::Buffer* buffer = item(model_.buffers, view->buffer);
    if (buffer == nullptr)
      return error("bufferView " + std::to_string(v) + " refers to buffer " + std::to_string(view->buffer) +
                   ", which does not exist");
    stride = strided && view->byteStride != 0 ? view->byteStride : elementSize;
    using U = unsigned __int128;  // sizes from the file
    const U end = count == 0 ? U(0) : U(stride) * (count - 1) + elementSize;
    if (byteOffset < 0 || stride < elementSize || U(byteOffset) + end > view->byteLength ||
        U(view->byteOffset) + view->byteLength > buffer->data.size())
      return error(what + ": " + std::to_string(count) + " elements of " + std::to_string(elementSize) +
                   " bytes do not fit its bufferView " + std::to_string(v) + " and its buffer");
    first = buffer->data.data() + view->byteOffset + std::size_t(byteOffset);
    return Status::success();
  }

  Status applySparse(const Accessor& accessor, const std::string& what, std::size_t elementSize,
                     std::vector<unsigned char>& out) const {
    const auto& sparse = accessor.sparse;
    const std::size_t isize = indexSize(sparse.indices.componentType);
    if (sparse.count < 1 || std::size_t(sparse.count) > accessor.count || isize == 0)
      return error(what + ": sparse.count must be from 1 to the accessor's count, its indices of an unsigned "
                          "integer type");
    const auto n = std::size_t(sparse.count);
    const unsigned char *indices = nullptr, *values = nullptr;
    std::size_t stride = 0;
    if (Status s = span(sparse.indices.bufferView, sparse.indices.byteOffset, n, isize, false, what + " sparse.indices",
                        indices, stride);
        !s)
      return s;
    if (Status s = span(sparse.values.bufferView, sparse.values.byteOffset, n, elementSize, false, what + " sparse.values",
                        values, stride);
        !s)
      return s;
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t i = readUnsigned(indices + k * isize, isize);
      if (i >= accessor.count)
        return error(what + ": sparse index " + std::to_string(i) + " is not below its count " + std::to_string(accessor.count));
      std::memcpy(&out[std::size_t(i) * elementSize], values + k * elementSize, elementSize);
    }
    return Status::success();
  }
};

// A node's own transform: its matrix, or translation * rotation * scale.
Status localMatrix(const tinygltf::Node& node, int n, const Reader& reader, glm::dmat4& m) {
  const std::string at = "nodes[" + std::to_string(n) + "].";
  auto wrongSize = [&](const char* key, std::size_t size, int wanted) {
    return reader.error(at + key + " has " + std::to_string(size) + " numbers; glTF 2.0 requires " + std::to_string(wanted));
  };
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16) return wrongSize("matrix", node.matrix.size(), 16);
    m = glm::make_mat4(node.matrix.data());  // column-major, as glTF
    return Status::success();
  }
  const auto& t = node.translation;
  const auto& r = node.rotation;
  const auto& s = node.scale;
  if (!t.empty() && t.size() != 3) return wrongSize("translation", t.size(), 3);
  if (!r.empty() && r.size() != 4) return wrongSize("rotation", r.size(), 4);
  if (!s.empty() && s.size() != 3) return wrongSize("scale", s.size(), 3);
  m = glm::dmat4(1.0);
  if (!t.empty()) m = glm::translate(m, glm::dvec3(t[0], t[1], t[2]));
  if (!r.empty()) m *= glm::mat4_cast(glm::dquat(r[3], r[0], r[1], r[2]));  // glTF writes x, y, z, w
  if (!s.empty()) m = glm::scale(m, glm::dvec3(s[0], s[1], s[2]));
  return Status::success();
}

struct Instance {
  int mesh;
  glm::dmat4 world;
};

// The meshes and cameras of scene `sceneIndex` with their world matrices. The nodes must form
// trees (one parent each, no cycle) whose roots the scene lists once each.
Status instances(const Model& model, int sceneIndex, const Reader& reader, std::vector<Instance>& out,
                 std::vector<GltfCameraNode>& cameras) {
  const std::size_t count = model.nodes.size();
  std::vector<int> parent(count, -1);
  for (std::size_t n = 0; n < count; ++n)
    for (int c : model.nodes[n].children) {
      if (!item(model.nodes, c))
        return reader.error("nodes[" + std::to_string(n) + "].children names node " + std::to_string(c) +
                            ", which does not exist");
      if (parent[std::size_t(c)] != -1)
        return reader.error("node " + std::to_string(c) + " is a child of node " + std::to_string(parent[std::size_t(c)]) +
                            " and of node " + std::to_string(n) + "; glTF 2.0 allows one parent");
      parent[std::size_t(c)] = int(n);
    }
  // With one parent each, a cycle is a walk up the parents that comes back to where it started.
  std::vector<std::size_t> walk(count, count);
  for (std::size_t s = 0; s < count; ++s) {
    std::size_t v = s;
    while (walk[v] == count) {
      walk[v] = s;
      if (parent[v] == -1) break;
      v = std::size_t(parent[v]);
    }
    if (parent[v] != -1 && walk[v] == s)
      return reader.error("nodes[" + std::to_string(v) + "] is its own ancestor (the node hierarchy has a cycle)");
  }
  const tinygltf::Scene& scene = model.scenes[std::size_t(sceneIndex)];
  std::vector<bool> listed(count);
  std::vector<std::pair<int, glm::dmat4>> stack;
  const std::string where = "scenes[" + std::to_string(sceneIndex) + "].nodes";
  for (int root : scene.nodes) {
    if (!item(model.nodes, root)) return reader.error(where + " names node " + std::to_string(root) + ", which does not exist");
    if (parent[std::size_t(root)] != -1)
      return reader.error(where + " names node " + std::to_string(root) + ", which is a child of node " +
                          std::to_string(parent[std::size_t(root)]) + "; a scene lists root nodes only");
    if (listed[std::size_t(root)]) return reader.error(where + " names node " + std::to_string(root) + " twice");
    listed[std::size_t(root)] = true;
    stack.emplace_back(root, glm::dmat4(1.0));
  }
  while (!stack.empty()) {
    const auto [n, parentWorld] = stack.back();
    stack.pop_back();
    const tinygltf::Node& node = model.nodes[std::size_t(n)];
    glm::dmat4 local;
    if (Status s = localMatrix(node, n, reader, local); !s) return s;
    const glm::dmat4 world = parentWorld * local;
    if (node.mesh != -1) {
      if (!item(model.meshes, node.mesh))
        return reader.error("nodes[" + std::to_string(n) + "].mesh is " + std::to_string(node.mesh) + ", which does not exist");
      out.push_back({node.mesh, world});
    }
    if (node.camera != -1) {
      if (!item(model.cameras, node.camera))
        return reader.error("nodes[" + std::to_string(n) + "].camera is " + std::to_string(node.camera) +
                            ", which does not exist");
      cameras.push_back({n, node.camera, world});
    }
    for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.emplace_back(*c, world);
  }
  return Status::success();
}

bool isTriangles(int mode) {
  return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

// How many triangles `n` vertices (or indices) make in `mode`.
std::uint64_t triangleCount(int mode, std::uint64_t n) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return n / 3;
  return n >= 3 ? n - 2 : 0;
}

// Appends primitive `p` of mesh `m` to `out`, transformed by `world`.
Status appendPrimitive(const Model& model, int m, std::size_t p, const glm::dmat4& world, const Reader& reader,
                       Mesh& out) {
  const tinygltf::Primitive& primitive = model.meshes[std::size_t(m)].primitives[p];
  const std::string which = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
  const auto position = primitive.attributes.find("POSITION");
  const int b = position == primitive.attributes.end() ? -1 : position->second;
  const Accessor* positions = item(model.accessors, b);
  if (positions == nullptr) return reader.error(which + " has no POSITION accessor");
  if (positions->componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || positions->type != TINYGLTF_TYPE_VEC3)
    return reader.error(which + ": its POSITION, accessor " + std::to_string(b) +
                        ", is not VEC3 of FLOAT (componentType 5126), the only kind read");
  std::vector<unsigned char> raw;
  if (Status s = reader.elements(b, 12, raw); !s) return s;
  const std::size_t vertices = positions->count;

  // Identical positions become one vertex; `remap` takes the primitive's vertex to the mesh's.
  std::unordered_map<Key, std::uint32_t, KeyHash> unique;
  std::vector<std::uint32_t> remap(vertices);
  for (std::size_t v = 0; v < vertices; ++v) {
    Key k;
    std::memcpy(&k, &raw[v * 12], 12);
    k = {k.x + 0.0f, k.y + 0.0f, k.z + 0.0f};  // -0 as +0
    const auto [it, added] = unique.try_emplace(k, std::uint32_t(0));
    if (added) {
      if (out.positions.size() >= std::numeric_limits<std::uint32_t>::max())
        return fileError(StatusCode::InvalidInput, reader.name(), "has more than 2^32 - 1 vertices");
      it->second = std::uint32_t(out.positions.size());
      const glm::dvec4 w = world * glm::dvec4(k.x, k.y, k.z, 1.0);
      out.positions.emplace_back(float(w.x), float(w.y), float(w.z));
    }
    remap[v] = it->second;
  }

  std::vector<std::uint32_t> indices;
  if (primitive.indices >= 0) {
    const Accessor* accessor = item(model.accessors, primitive.indices);
    const std::size_t size = accessor ? indexSize(accessor->componentType) : 0;
    if (size == 0 || accessor->type != TINYGLTF_TYPE_SCALAR)
      return reader.error(which + ": its indices, accessor " + std::to_string(primitive.indices) +
                          ", are not SCALAR of an unsigned integer type");
    std::vector<unsigned char> bytes;
    if (Status s = reader.elements(primitive.indices, size, bytes); !s) return s;
    indices.resize(accessor->count);
    for (std::size_t k = 0; k < accessor->count; ++k) {
      const std::uint32_t index = readUnsigned(&bytes[k * size], size);
      if (index >= vertices)
        return reader.error(which + ": index " + std::to_string(index) + " (element " + std::to_string(k) +
                            " of accessor " + std::to_string(primitive.indices) + ") is out of range: its POSITION, " +
                            "accessor " + std::to_string(b) + ", has " + std::to_string(vertices) + " vertices");
      indices[k] = remap[index];
    }
  } else {
    indices = remap;
  }
  const std::size_t n = indices.size();
  const std::uint64_t triangles = triangleCount(primitive.mode, n);
  for (std::size_t t = 0; t < triangles; ++t) {
    std::size_t a, c, d;
    if (primitive.mode == TINYGLTF_MODE_TRIANGLES) {
      a = 3 * t, c = 3 * t + 1, d = 3 * t + 2;
    } else if (primitive.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {  // every other one turned, to keep the winding
      a = t, c = t + 1 + t % 2, d = t + 2 - t % 2;
    } else {  // a fan around the first vertex
      a = t + 1, c = t + 2, d = 0;
    }
    out.indices.insert(out.indices.end(), {indices[a], indices[c], indices[d]});
  }
  return Status::success();
}

}  // namespace

Status gltfTriangles(const Model& model, std::string_view name, Mesh& out, std::vector<GltfCameraNode>* cameras) {
  const Reader reader(model, name);
  if (model.scenes.empty()) return reader.error("there is no scene (no \"scenes\"), so nothing would be drawn");
  const int scene = model.defaultScene < 0 ? 0 : model.defaultScene;
  if (std::size_t(scene) >= model.scenes.size())
    return reader.error("\"scene\" is " + std::to_string(scene) + ", which does not exist");
  std::vector<Instance> meshes;
  std::vector<GltfCameraNode> cameraNodes;
  if (Status s = instances(model, scene, reader, meshes, cameraNodes); !s) return s;
  // The walk is depth first; the views follow the nodes' own order.
  std::sort(cameraNodes.begin(), cameraNodes.end(), [](const auto& a, const auto& b) { return a.node < b.node; });

  // The triangles first, to refuse too many before reading any.
  std::uint64_t triangles = 0;
  for (const Instance& instance : meshes) {
    const auto& primitives = model.meshes[std::size_t(instance.mesh)].primitives;
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      if (!isTriangles(primitives[p].mode)) continue;  // points and lines are left out
      const auto position = primitives[p].attributes.find("POSITION");
      const Accessor* counted = item(model.accessors, primitives[p].indices >= 0 ? primitives[p].indices
                                                      : position == primitives[p].attributes.end() ? -1
                                                                                                   : position->second);
      if (counted == nullptr) continue;  // appendPrimitive names it
      const std::uint64_t add = triangleCount(primitives[p].mode, counted->count);
      triangles = add > std::numeric_limits<std::uint64_t>::max() - triangles ? std::numeric_limits<std::uint64_t>::max()
                                                                              : triangles + add;
    }
  }
  if (triangles > kMaxMeshTriangles)
    return fileError(StatusCode::InvalidInput, name,
                     "has " + std::to_string(triangles) + " triangles, more than the limit of " +
                         std::to_string(kMaxMeshTriangles));
  Mesh mesh;
  mesh.indices.reserve(std::size_t(triangles) * 3);
  for (const Instance& instance : meshes) {
    const auto& primitives = model.meshes[std::size_t(instance.mesh)].primitives;
    for (std::size_t p = 0; p < primitives.size(); ++p)
      if (isTriangles(primitives[p].mode))
        if (Status s = appendPrimitive(model, instance.mesh, p, instance.world, reader, mesh); !s) return s;
  }
  out = std::move(mesh);
  if (cameras) *cameras = std::move(cameraNodes);
  return Status::success();
}

}  // namespace sao::scenes::detail
