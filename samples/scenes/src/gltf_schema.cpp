// The glTF 2.0 schema's member types, as a table: each kind of object lists its members.
#include "gltf_schema.h"

#include <cmath>
#include <initializer_list>
#include <string>

#include "file_checks.h"

namespace sao::scenes::detail {

namespace {

using nlohmann::json;

enum class Type { Object, String, UInt, Number, Bool, UIntArray, NumberArray, StringArray, ObjectArray, UIntMap };

struct Member;
using Members = std::initializer_list<Member>;

struct Member {
  const char* key;
  Type type;
  const Members* fields = nullptr;  // for Object and ObjectArray: the members of each object
};

// The members of every kind of object, in the specification's order.
const Members kTextureInfo = {{"index", Type::UInt}, {"texCoord", Type::UInt}, {"scale", Type::Number},
                              {"strength", Type::Number}};
const Members kPbr = {{"baseColorFactor", Type::NumberArray}, {"baseColorTexture", Type::Object, &kTextureInfo},
                      {"metallicFactor", Type::Number}, {"roughnessFactor", Type::Number},
                      {"metallicRoughnessTexture", Type::Object, &kTextureInfo}};
const Members kMaterial = {{"pbrMetallicRoughness", Type::Object, &kPbr}, {"normalTexture", Type::Object, &kTextureInfo},
                           {"occlusionTexture", Type::Object, &kTextureInfo},
                           {"emissiveTexture", Type::Object, &kTextureInfo}, {"emissiveFactor", Type::NumberArray},
                           {"alphaMode", Type::String}, {"alphaCutoff", Type::Number}, {"doubleSided", Type::Bool}};
const Members kPrimitive = {{"attributes", Type::UIntMap}, {"indices", Type::UInt}, {"material", Type::UInt},
                            {"mode", Type::UInt}, {"targets", Type::ObjectArray}};
const Members kMesh = {{"primitives", Type::ObjectArray, &kPrimitive}, {"weights", Type::NumberArray}};
const Members kNode = {{"camera", Type::UInt}, {"children", Type::UIntArray}, {"skin", Type::UInt},
                       {"matrix", Type::NumberArray}, {"mesh", Type::UInt}, {"rotation", Type::NumberArray},
                       {"scale", Type::NumberArray}, {"translation", Type::NumberArray},
                       {"weights", Type::NumberArray}};
const Members kSparseIndices = {{"bufferView", Type::UInt}, {"byteOffset", Type::UInt}, {"componentType", Type::UInt}};
const Members kSparseValues = {{"bufferView", Type::UInt}, {"byteOffset", Type::UInt}};
const Members kSparse = {{"count", Type::UInt}, {"indices", Type::Object, &kSparseIndices},
                         {"values", Type::Object, &kSparseValues}};
const Members kAccessor = {{"bufferView", Type::UInt}, {"byteOffset", Type::UInt}, {"componentType", Type::UInt},
                           {"normalized", Type::Bool}, {"count", Type::UInt}, {"type", Type::String},
                           {"max", Type::NumberArray}, {"min", Type::NumberArray},
                           {"sparse", Type::Object, &kSparse}};
const Members kBufferView = {{"buffer", Type::UInt}, {"byteOffset", Type::UInt}, {"byteLength", Type::UInt},
                             {"target", Type::UInt}};  // byteStride: gltf_accessors.cpp
const Members kBuffer = {{"uri", Type::String}, {"byteLength", Type::UInt}};
const Members kTexture = {{"sampler", Type::UInt}, {"source", Type::UInt}};
const Members kImage = {{"uri", Type::String}, {"mimeType", Type::String}, {"bufferView", Type::UInt}};
const Members kSampler = {{"magFilter", Type::UInt}, {"minFilter", Type::UInt}, {"wrapS", Type::UInt},
                          {"wrapT", Type::UInt}};
const Members kTarget = {{"node", Type::UInt}, {"path", Type::String}};
const Members kChannel = {{"sampler", Type::UInt}, {"target", Type::Object, &kTarget}};
const Members kAnimationSampler = {{"input", Type::UInt}, {"interpolation", Type::String}, {"output", Type::UInt}};
const Members kAnimation = {{"channels", Type::ObjectArray, &kChannel},
                            {"samplers", Type::ObjectArray, &kAnimationSampler}};
const Members kSkin = {{"inverseBindMatrices", Type::UInt}, {"skeleton", Type::UInt}, {"joints", Type::UIntArray}};
const Members kOrthographic = {{"xmag", Type::Number}, {"ymag", Type::Number}, {"zfar", Type::Number},
                               {"znear", Type::Number}};
const Members kPerspective = {{"aspectRatio", Type::Number}, {"yfov", Type::Number}, {"zfar", Type::Number},
                              {"znear", Type::Number}};
const Members kCamera = {{"orthographic", Type::Object, &kOrthographic},
                         {"perspective", Type::Object, &kPerspective}, {"type", Type::String}};
const Members kAsset = {{"copyright", Type::String}, {"generator", Type::String}, {"version", Type::String},
                        {"minVersion", Type::String}};
const Members kScene = {{"nodes", Type::UIntArray}};
const Members kRoot = {{"extensionsUsed", Type::StringArray}, {"extensionsRequired", Type::StringArray},
                       {"accessors", Type::ObjectArray, &kAccessor}, {"animations", Type::ObjectArray, &kAnimation},
                       {"asset", Type::Object, &kAsset}, {"buffers", Type::ObjectArray, &kBuffer},
                       {"bufferViews", Type::ObjectArray, &kBufferView}, {"cameras", Type::ObjectArray, &kCamera},
                       {"images", Type::ObjectArray, &kImage}, {"materials", Type::ObjectArray, &kMaterial},
                       {"meshes", Type::ObjectArray, &kMesh}, {"nodes", Type::ObjectArray, &kNode},
                       {"samplers", Type::ObjectArray, &kSampler}, {"scene", Type::UInt},
                       {"scenes", Type::ObjectArray, &kScene}, {"skins", Type::ObjectArray, &kSkin},
                       {"textures", Type::ObjectArray, &kTexture}};

bool isUInt(const json& v) {
  if (v.is_number_unsigned()) return true;
  if (v.is_number_integer()) return v.get<std::int64_t>() >= 0;
  if (!v.is_number_float()) return false;
  const double d = v.get<double>();
  return d >= 0 && d < 0x1p53 && d == std::floor(d);  // 2.0 is a whole number in JSON too
}

std::string what(const json& v) {
  if (v.is_null()) return "null";
  if (v.is_boolean()) return "a boolean";
  if (v.is_number()) {
    std::string text = v.dump();
    return "the number " + (text.size() > 32 ? text.substr(0, 32) + "..." : text);
  }
  if (v.is_string()) return "a string";
  return v.is_array() ? "an array" : "an object";
}

class Checker {
 public:
  explicit Checker(std::string_view name) : name_(name) {}

  Status object(const json& o, const Members& members, const std::string& path) {
    if (!o.is_object()) return wrong(path, o, "an object");
    for (const Member& m : members) {
      const auto it = o.find(m.key);
      if (it == o.end()) continue;
      const std::string at = path.empty() ? m.key : path + "." + m.key;
      if (Status s = value(*it, m, at); !s) return s;
    }
    if (const auto ext = o.find("extensions"); ext != o.end()) {
      const std::string at = path.empty() ? "extensions" : path + ".extensions";
      if (!ext->is_object()) return wrong(at, *ext, "an object");
      // Each extension is an object of its own (its members are the extension's business).
      for (const auto& [key, item] : ext->items())
        if (!item.is_object()) return wrong(at + "." + key, item, "an object");
    }
    if (const auto n = o.find("name"); n != o.end() && !n->is_string() && !path.empty())
      return wrong(path + ".name", *n, "a string");
    return Status::success();
  }

 private:
  std::string_view name_;

  Status wrong(const std::string& path, const json& v, const std::string& wanted) const {
    return fileError(StatusCode::IoError, name_,
                     "glTF: " + (path.empty() ? std::string("the document") : path) + " is " + what(v) +
                         "; glTF 2.0 requires " + wanted);
  }

  // An array whose every item is `element`.
  Status array(const json& a, const std::string& path, const char* element, bool (*ok)(const json&)) const {
    if (!a.is_array()) return wrong(path, a, std::string("an array of ") + element + "s");
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!ok(a[i])) return wrong(path + "[" + std::to_string(i) + "]", a[i], element);
    return Status::success();
  }

  Status value(const json& v, const Member& m, const std::string& path) {
    switch (m.type) {
      case Type::Object: return object(v, *m.fields, path);
      case Type::String: return v.is_string() ? Status::success() : wrong(path, v, "a string");
      case Type::UInt: return isUInt(v) ? Status::success() : wrong(path, v, "a non-negative integer");
      case Type::Number: return v.is_number() ? Status::success() : wrong(path, v, "a number");
      case Type::Bool: return v.is_boolean() ? Status::success() : wrong(path, v, "true or false");
      case Type::UIntArray: return array(v, path, "a non-negative integer", isUInt);
      case Type::NumberArray: return array(v, path, "a number", [](const json& x) { return x.is_number(); });
      case Type::StringArray: return array(v, path, "a string", [](const json& x) { return x.is_string(); });
      case Type::UIntMap:
        if (!v.is_object()) return wrong(path, v, "an object");
        for (const auto& [key, item] : v.items())
          if (!isUInt(item)) return wrong(path + "." + key, item, "a non-negative integer");
        return Status::success();
      case Type::ObjectArray:
        if (!v.is_array()) return wrong(path, v, "an array");
        for (std::size_t i = 0; i < v.size(); ++i) {
          const std::string at = path + "[" + std::to_string(i) + "]";
          if (m.fields == nullptr) {  // morph targets: maps of attribute names to accessors
            if (Status s = value(v[i], {m.key, Type::UIntMap}, at); !s) return s;
          } else if (Status s = object(v[i], *m.fields, at); !s) {
            return s;
          }
        }
        return Status::success();
    }
    return Status::success();
  }
};

}  // namespace

Status checkGltfTypes(const json& doc, std::string_view name) {
  Checker checker(name);
  if (Status s = checker.object(doc, kRoot, ""); !s) return s;
  // The schema's minimum byteLength of a buffer and of a buffer view is 1.
  for (const char* key : {"buffers", "bufferViews"}) {
    const auto list = doc.find(key);
    for (std::size_t i = 0; list != doc.end() && i < list->size(); ++i) {
      const auto length = (*list)[i].find("byteLength");
      if (length != (*list)[i].end() && length->get<double>() == 0)
        return fileError(StatusCode::IoError, name,
                         "glTF: " + std::string(key) + "[" + std::to_string(i) + "].byteLength is 0; glTF 2.0 requires at least 1");
    }
  }
  return Status::success();
}

}  // namespace sao::scenes::detail
