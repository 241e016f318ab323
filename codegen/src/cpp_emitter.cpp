#include "cpp_emitter.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "effect_rules.h"
#include "target_rules.h"

namespace sao::codegen {
namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

std::string number(double v) {  // round-trips a double, deterministic
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  std::string s = buf;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

std::string floatLiteral(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  std::string s = buf;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s + "f";
}

const char* cppType(const std::string& glsl) {
  if (glsl == "float") return "float";
  if (glsl == "int") return "std::int32_t";
  if (glsl == "uint") return "std::uint32_t";
  if (glsl == "vec2") return "Float2";
  if (glsl == "ivec2") return "Int2";
  if (glsl == "uvec2") return "UInt2";
  if (glsl == "vec4") return "Float4";
  if (glsl == "ivec4") return "Int4";
  if (glsl == "uvec4") return "UInt4";
  return "Float4x4";  // mat4
}

const char* kindName(ResourceKind k) {
  switch (k) {
    case ResourceKind::Input: return "ResourceKind::Input";
    case ResourceKind::Image: return "ResourceKind::Image";
    default: return "ResourceKind::Output";
  }
}

std::string formatName(const std::string& f) {
  const auto facts = findFormat(f);
  return "Format::" + std::string(facts ? facts->enumName : "Depth");
}

// gen::Format and gen::kFormatInfo, from formats.h's table.
void emitFormats(std::ostream& h) {
  h << "enum class Format : std::uint8_t {";
  for (const FormatFacts& f : formats()) h << (&f == formats().data() ? " " : ", ") << f.enumName;
  h << " };\n"
    << "// What each format is (codegen/src/formats.cpp, the one table): channels, bytes per texel, the GL\n"
    << "// internal format and the VkFormat it is (the API's enumerant values), whether a pass may store to\n"
    << "// it, whether it is 8-bit unsigned normalised. Indexed by Format.\n"
    << "struct FormatInfo {\n  std::string_view name;\n  std::uint32_t channels;\n  std::uint32_t bytesPerTexel;\n"
    << "  std::uint32_t glInternalFormat;\n  std::uint32_t vkFormat;\n  bool colour;\n  bool unorm;\n};\n"
    << "inline constexpr std::array<FormatInfo, " << formats().size() << "> kFormatInfo = {{\n";
  for (const FormatFacts& f : formats())
    h << "  {\"" << f.name << "\", " << f.channels << ", " << f.bytesPerTexel << ", " << f.glInternalFormat << ", "
      << f.vkFormat << ", " << (f.colour ? "true" : "false") << ", " << (f.unorm ? "true" : "false") << "},\n";
  h << "}};\n"
    << "inline constexpr const FormatInfo& formatInfo(Format f) { return kFormatInfo[static_cast<std::size_t>(f)]; }\n";
}

// The kind=input resources as ids and as named members of InputSet<T>, which every API's Inputs
// derives from: an input declared in the effect is a field of each backend's Inputs, and the
// backends reach it by id (no backend names an optional input).
void emitInputSet(std::ostream& h, const Effect& e) {
  std::vector<const Resource*> inputs;
  for (const auto& r : e.resources)
    if (r.kind == ResourceKind::Input) inputs.push_back(&r);
  h << "// ---- Inputs: the kind=input resources, in declaration order.\n"
    << "inline constexpr std::array<ResourceId, " << inputs.size() << "> kInputIds = {{";
  for (size_t i = 0; i < inputs.size(); ++i) h << (i ? ", " : "") << "ResourceId::" << inputs[i]->name;
  h << "}};\n"
    << "// One T per input, by name (the resource's) and by id: an API's Inputs holds its images so.\n"
    << "template <typename T>\nstruct InputSet {\n";
  for (const Resource* r : inputs) {
    std::string doc = r->doc;
    std::replace(doc.begin(), doc.end(), '\n', ' ');
    h << "  T " << r->name << "{};  // " << doc << "\n";
  }
  if (inputs.empty()) {  // an effect without inputs (codegen's own test effects)
    h << "  bool operator==(const InputSet&) const = default;\n};\n\n";
    return;
  }
  h << "  // `id` must be one of kInputIds.\n"
    << "  T& operator[](ResourceId id) { return const_cast<T&>(std::as_const(*this)[id]); }\n"
    << "  const T& operator[](ResourceId id) const {\n    switch (id) {\n";
  for (const Resource* r : inputs) h << "      case ResourceId::" << r->name << ": return " << r->name << ";\n";
  h << "      default: break;\n    }\n    return " << inputs.front()->name << ";\n  }\n"
    << "  bool operator==(const InputSet&) const = default;\n};\n\n";
}

// Shader text as a raw string split in chunks (compilers limit one literal's length).
std::string glslLiteral(const std::string& text) {
  std::string out;
  const size_t chunk = 8000;
  for (size_t i = 0; i < text.size(); i += chunk)
    out += "R\"sao_glsl(" + text.substr(i, chunk) + ")sao_glsl\"\n";
  return out.empty() ? "\"\"" : out;
}

// Float components widened to T, integer members unchanged: the same block for C++ code that
// evaluates the shaders' math in another precision (the CPU reference's double path), so no
// hand-written copy of the block exists anywhere.
const char* widenedType(const std::string& glsl) {
  if (glsl == "float") return "T";
  if (glsl == "vec2") return "Vec2Of<T>";
  if (glsl == "vec4") return "Vec4Of<T>";
  if (glsl == "mat4") return "Mat4Of<T>";
  return cppType(glsl);  // int, uint and their vectors stay as they are
}

std::string widenedValue(const std::string& glsl, const std::string& src) {
  if (glsl == "float") return "T(" + src + ")";
  if (glsl == "vec2") return "Vec2Of<T>{T(" + src + ".x), T(" + src + ".y)}";
  if (glsl == "vec4") return "Vec4Of<T>{T(" + src + ".x), T(" + src + ".y), T(" + src + ".z), T(" + src + ".w)}";
  if (glsl == "mat4") return "widenMat4<T>(" + src + ")";
  return src;
}

void emitWidenedBlock(std::ostringstream& h, const ParamBlock& b) {
  h << "// ---- '" << b.name << "' with its float components widened to T (T = float: the same values).\n"
    << "template <typename T> struct Vec2Of { T x, y; };\n"
    << "template <typename T> struct Vec4Of {\n  T x, y, z, w;\n"
    << "  T operator[](int i) const { return i == 0 ? x : i == 1 ? y : i == 2 ? z : w; }\n};\n"
    << "template <typename T> struct Mat4Of { T m[16]; };  // column-major\n"
    << "template <typename T> Mat4Of<T> widenMat4(const Float4x4& f) {\n"
    << "  Mat4Of<T> r{};\n  for (int i = 0; i < 16; ++i) r.m[i] = T(f.m[i]);\n  return r;\n}\n"
    << "template <typename T>\nstruct " << b.name << "As {\n";
  for (const auto& m : b.members) {
    h << "  " << widenedType(m.glslType) << " " << m.name;
    if (m.arraySize > 0) h << "[" << m.arraySize << "]";
    h << ";\n";
  }
  h << "  explicit " << b.name << "As(const " << b.name << "& p) {\n";
  for (const auto& m : b.members) {
    if (m.arraySize > 0)
      h << "    for (int i = 0; i < " << m.arraySize << "; ++i) " << m.name << "[i] = "
        << widenedValue(m.glslType, "p." + m.name + "[i]") << ";\n";
    else
      h << "    " << m.name << " = " << widenedValue(m.glslType, "p." + m.name) << ";\n";
  }
  h << "  }\n};\n"
    << "template <typename T>\nusing ParamBlockAs = " << b.name << "As<T>;\n\n";
}

const char* selectName(VariantSelect v) {
  switch (v) {
    case VariantSelect::Setting: return "VariantSelect::Setting";
    case VariantSelect::Input: return "VariantSelect::Input";
    case VariantSelect::Output: return "VariantSelect::Output";
    case VariantSelect::Multisampled: return "VariantSelect::Multisampled";
    default: return "VariantSelect::Default";
  }
}

const char* compareName(CompareOp op) {
  switch (op) {
    case CompareOp::Eq: return "Compare::Eq";
    case CompareOp::Ne: return "Compare::Ne";
    case CompareOp::Lt: return "Compare::Lt";
    case CompareOp::Le: return "Compare::Le";
    case CompareOp::Gt: return "Compare::Gt";
    default: return "Compare::Ge";
  }
}

std::string conditionValue(const Effect& e, const std::optional<SettingCondition>& c) {
  if (!c) return "{false, SettingId{}, Compare::Eq, 0.0}";
  return std::string("{true, SettingId::") + conditionSettingName(e, c->setting) + ", " + compareName(c->op) + ", " +
         number(c->value) + "}";
}

// The C++ enumerator of a preset: its lower-case name with the first letter upper-cased.
std::string presetEnumerator(const std::string& name) {
  std::string out = name;
  out[0] = static_cast<char>(out[0] - 'a' + 'A');
  return out;
}

void emitPresets(std::ostringstream& h, const Effect& e) {
  h << "// ---- Presets: named setting values; settings a preset does not list keep their defaults.\n"
    << "enum class Preset : std::uint32_t {\n";
  for (const auto& p : e.presets) h << "  " << presetEnumerator(p.name) << ",\n";
  h << "};\nstruct PresetValue {\n  SettingId setting;\n  double value;  // as setSettingValue takes it\n};\n";
  for (const auto& p : e.presets) {
    if (p.values.empty()) continue;
    h << "inline constexpr PresetValue kPresetValues_" << p.name << "[] = {";
    for (size_t i = 0; i < p.values.size(); ++i)
      h << (i ? ", " : "") << "{SettingId::" << e.settings[p.values[i].first].name << ", " << number(p.values[i].second)
        << "}";
    h << "};\n";
  }
  h << "struct PresetInfo {\n  Preset preset;\n  std::string_view name;\n  std::string_view summary;\n"
    << "  std::span<const PresetValue> values;\n};\n"
    << "inline constexpr std::array<PresetInfo, " << e.presets.size() << "> kPresets = {{\n";
  for (const auto& p : e.presets)
    h << "  {Preset::" << presetEnumerator(p.name) << ", " << quoted(p.name) << ", " << quoted(p.doc) << ", "
      << (p.values.empty() ? std::string("{}") : "kPresetValues_" + p.name) << "},\n";
  h << "}};\n\n";
}

// `#pragma sao inert`: the settings that have no effect while a condition holds; `#pragma sao
// refuse`: the settings plan() refuses at a value other than their default while one holds.
void emitSettingRules(std::ostringstream& h, const Effect& e) {
  h << "// ---- Rules on a setting: `setting` has no effect (kInertRules: its value reaches no pass that runs), or\n"
    << "// is refused at any value but its default (kRefusalRules: plan() fails), while `when` holds.\n"
    << "struct InertRule {\n  SettingId setting;\n  SettingCondition when;\n"
    << "  std::string_view whenText;  // `when` in words, a derived setting's terms spelled out\n"
    << "  std::string_view fixText;   // what makes `when` false\n"
    << "  std::string_view reason;    // why the rule holds\n};\n";
  const auto list = [&](const char* name, const std::vector<InertRule>& rules) {
    h << "inline constexpr std::array<InertRule, " << rules.size() << "> " << name << " = {{\n";
    for (const auto& r : rules)
      h << "  {SettingId::" << e.settings[r.setting].name << ", " << conditionValue(e, r.when) << ", "
        << quoted(r.whenText) << ", " << quoted(r.fixText) << ", " << quoted(r.doc) << "},\n";
    h << "}};\n";
  };
  list("kInertRules", e.inert);
  list("kRefusalRules", e.refusals);
  h << "\n";
}

// The push constants of the passes that declare them (one block for all: main.cpp checks it), each
// member a copy of the parameter block's member of the same name (checked there too).
void emitPushConstants(std::ostringstream& h, const ParamBlock& b, const std::vector<CompiledPassVariant>& pvs) {
  const SpirvFacts* facts = pushConstantFacts(pvs);
  h << "// ---- Push constants";
  if (facts) h << " (block '" << facts->pushConstantBlock << "', Vulkan only)";
  h << ": the passes whose PassVariantInfo::pushConstantBytes is not 0 take them; each member is the\n"
    << "// parameter block's member of the same name (pushConstantsOf).\n"
    << "struct PushConstants {\n";
  if (facts)
    for (const auto& m : facts->pushConstants)
      h << "  " << (m.glslType == "float" ? "float" : m.glslType == "uint" ? "std::uint32_t" : "std::int32_t") << " "
        << m.name << ";  // offset " << m.offset << "\n";
  h << "};\n"
    << "inline constexpr std::uint32_t kPushConstantBytes = " << (facts ? facts->pushConstantBytes : 0) << ";\n"
    << "inline PushConstants pushConstantsOf(const " << b.name << "& " << (facts ? "p" : "") << ") { return {";
  if (facts)
    for (std::size_t i = 0; i < facts->pushConstants.size(); ++i) h << (i ? ", " : "") << "p." << facts->pushConstants[i].name;
  h << "}; }\n\n";
}

}  // namespace

const SpirvFacts* pushConstantFacts(const std::vector<CompiledPassVariant>& passVariants) {
  for (const auto& c : passVariants)
    if (c.facts.pushConstantBytes > 0) return &c.facts;
  return nullptr;
}

// The effect's `target gles` rule as two functions of the format (target_rules.h decides each).
static void emitGlesRule(std::ostream& h, const Effect& e) {
  std::ostringstream stores, refused;
  for (const FormatFacts& f : formats()) {
    if (!f.colour) continue;
    const auto es = glesStorageFormat(e, std::string(f.name));
    if (!es) refused << "    case Format::" << f.enumName << ":\n";
    else if (*es != f.name) stores << "    case Format::" << f.enumName << ": return " << formatName(*es) << ";\n";
  }
  h << "// OpenGL ES 3.1 (the effect's `target gles` rule): the format an image of format f is stored in\n"
    << "// there (f itself where ES stores it), and whether the effect has no GLES form for f (a refused\n"
    << "// output format: its variants have no GLSL ES).\n"
    << "constexpr Format glesStorageFormat(Format f) {\n  switch (f) {\n" << stores.str()
    << "    default: return f;\n  }\n}\n"
    << "constexpr bool glesRefuses(Format f) {\n  switch (f) {\n" << refused.str()
    << (refused.str().empty() ? "" : "      return true;\n") << "    default: return false;\n  }\n}\n\n";
}

GeneratedCode emitCpp(const Effect& e, const std::vector<CompiledPassVariant>& pvs,
                      const std::vector<std::string>& glslBlobs, const std::vector<std::vector<uint32_t>>& spirvBlobs,
                      const std::vector<std::string>& esslBlobs) {
  std::ostringstream h;
  h << "// Generated by sao-shaderc from the annotated effect '" << e.name << "'. Do not edit.\n"
    << "#pragma once\n#include <array>\n#include <cstddef>\n#include <cstdint>\n#include <span>\n"
    << "#include <string_view>\n#include <utility>\n\nnamespace sao::gen {\n\n"
    << "inline constexpr std::string_view kEffectName = " << quoted(e.name) << ";\n"
    << "inline constexpr int kEffectVersion = " << e.version << ";\n\n";

  // --- settings
  h << "// ---- Settings: defaults as declared; validate with the metadata below.\n"
    << "struct Settings {\n";
  for (const auto& s : e.settings) {
    h << "  ";
    if (s.type == ScalarType::Float) h << "float " << s.name << " = " << floatLiteral(s.defaultValue);
    else if (s.type == ScalarType::Int) h << "std::int32_t " << s.name << " = " << static_cast<long long>(s.defaultValue);
    else h << "bool " << s.name << " = " << (s.defaultValue != 0 ? "true" : "false");
    h << ";  // " << s.doc << (s.unit.empty() ? "" : " [" + s.unit + "]") << "\n";
  }
  h << "  bool operator==(const Settings&) const = default;\n};\n\n";
  h << "enum class SettingType : std::uint8_t { Float, Int, Bool };\n"
    << "enum class SettingId : std::uint32_t {\n";
  for (const auto& s : e.settings) h << "  " << s.name << ",\n";
  for (const auto& d : e.derived) h << "  " << d.name << ",  // derived: " << d.doc << "\n";
  h << "};\n"
    << "struct SettingInfo {\n  std::string_view name;\n  SettingType type;\n  double defaultValue;\n"
    << "  double minValue;\n  double maxValue;\n  std::string_view unit;\n  std::string_view doc;\n"
    << "  std::span<const double> allowedValues;  // values=: the only values accepted; empty: the whole range\n};\n";
  for (const auto& s : e.settings) {
    if (s.allowed.empty()) continue;
    h << "inline constexpr double kAllowed_" << s.name << "[] = {";
    for (size_t i = 0; i < s.allowed.size(); ++i) h << (i ? ", " : "") << number(s.allowed[i]);
    h << "};\n";
  }
  h << "inline constexpr std::array<SettingInfo, " << e.settings.size() << "> kSettings = {{\n";
  for (const auto& s : e.settings) {
    const char* t = s.type == ScalarType::Float ? "Float" : s.type == ScalarType::Int ? "Int" : "Bool";
    h << "  {" << quoted(s.name) << ", SettingType::" << t << ", " << number(s.defaultValue) << ", "
      << number(s.minValue) << ", " << number(s.maxValue) << ", " << quoted(s.unit) << ", " << quoted(s.doc) << ", "
      << (s.allowed.empty() ? std::string("{}") : "kAllowed_" + s.name) << "},\n";
  }
  h << "}};\n"
    << "// Reads or writes one setting as a double (ints and bools exactly). A derived setting (a SettingId\n"
    << "// past kSettings) reads 1 when all its terms hold, else 0; writing it does nothing.\n"
    << "double settingValue(const Settings& s, SettingId id);\n"
    << "void setSettingValue(Settings& s, SettingId id, double value);\n\n";
  emitPresets(h, e);

  // --- constants
  h << "// ---- Compile-time constants (also #defined in every shader).\n";
  for (const auto& c : e.constants) {
    const char* t = c.type == "int" ? "std::int32_t" : c.type == "uint" ? "std::uint32_t" : "float";
    h << "inline constexpr " << t << " " << c.name << " = " << c.value << (c.type == "float" ? "f" : "")
      << ";  // " << c.doc << "\n";
  }

  // --- parameter block
  const ParamBlock& b = *e.block;
  h << "\n// ---- The std140 parameter block '" << b.name << "', binding 0, mirrored with explicit padding.\n"
    << "struct Float2 { float x, y; };\nstruct Int2 { std::int32_t x, y; };\nstruct UInt2 { std::uint32_t x, y; };\n"
    << "struct Float4 { float x, y, z, w; };\nstruct Int4 { std::int32_t x, y, z, w; };\n"
    << "struct UInt4 { std::uint32_t x, y, z, w; };\nstruct Float4x4 { float m[16]; };  // column-major\n\n"
    << "struct " << b.name << " {\n";
  int offset = 0, pad = 0;
  for (const auto& m : b.members) {
    if (m.offset > offset) h << "  std::uint8_t sao_pad" << pad++ << "[" << (m.offset - offset) << "];\n";
    h << "  " << cppType(m.glslType) << " " << m.name;
    if (m.arraySize > 0) h << "[" << m.arraySize << "]";
    h << ";\n";
    offset = m.offset + m.size;
  }
  if (b.size > offset) h << "  std::uint8_t sao_pad" << pad++ << "[" << (b.size - offset) << "];\n";
  h << "};\n";
  for (const auto& m : b.members)
    h << "static_assert(offsetof(" << b.name << ", " << m.name << ") == " << m.offset << ");\n";
  h << "static_assert(sizeof(" << b.name << ") == " << b.size << ");\n"
    << "using ParamBlock = " << b.name << ";\n\n";
  emitWidenedBlock(h, b);
  emitPushConstants(h, b, pvs);

  // --- variants
  h << "// ---- Variants: compile-time switches; a key holds one value per variant.\n"
    << "inline constexpr std::size_t kVariantCount = " << e.variants.size() << ";\n"
    << "using VariantValues = std::array<std::int32_t, kVariantCount>;  // -1 in tables: any value\n"
    << "enum class VariantId : std::uint32_t {\n";
  for (const auto& v : e.variants) h << "  " << v.name << ",\n";
  h << "};\n"
    << "// What gives a variant its value when the effect is planned.\n"
    << "enum class VariantSelect : std::uint8_t {\n"
    << "  Default,  // always defaultValue\n"
    << "  Setting,  // the setting SettingId(selectIndex), a bool or an int with values=[0,1]: its value\n"
    << "  Input,    // the kind=input resource ResourceId(selectIndex): 1 when the user supplies it\n"
    << "  Output,   // the kind=output resource ResourceId(selectIndex): the index of its image's format in its formats\n"
    << "  Multisampled,  // the kind=input resource ResourceId(selectIndex): 1 when it has several samples per texel\n"
    << "};\n"
    << "struct VariantInfo {\n  std::string_view name;\n  std::span<const std::int32_t> values;\n"
    << "  std::int32_t defaultValue;\n  VariantSelect select;\n  std::uint32_t selectIndex;\n"
    << "  std::string_view doc;\n};\n";
  for (const auto& v : e.variants) {
    h << "inline constexpr std::int32_t kVariantValues_" << v.name << "[] = {";
    for (size_t i = 0; i < v.values.size(); ++i) h << (i ? ", " : "") << v.values[i];
    h << "};\n";
  }
  h << "inline constexpr std::array<VariantInfo, kVariantCount> kVariants = {{\n";
  for (const auto& v : e.variants)
    h << "  {" << quoted(v.name) << ", kVariantValues_" << v.name << ", " << v.defaultValue << ", "
      << selectName(v.select) << ", " << (v.selectIndex < 0 ? 0 : v.selectIndex) << ", " << quoted(v.doc) << "},\n";
  h << "}};\nstruct Exclusion {\n  VariantValues values;  // -1: not part of the exclusion\n  std::string_view reason;\n};\n"
    << "inline constexpr std::array<Exclusion, " << e.exclusions.size() << "> kExclusions = {{\n";
  for (const auto& x : e.exclusions) {
    std::vector<int> vals(e.variants.size(), -1);
    for (auto [vi, val] : x.terms) vals[vi] = val;
    h << "  {{";
    for (size_t i = 0; i < vals.size(); ++i) h << (i ? ", " : "") << vals[i];
    h << "}, " << quoted(x.reason) << "},\n";
  }
  h << "}};\n"
    << "// The reason a combination is excluded, or empty when it is allowed.\n"
    << "std::string_view exclusionReason(const VariantValues& values);\n\n";

  // --- resources
  h << "// ---- Resources: inputs, effect-owned images, and the output.\n"
    << "enum class ResourceKind : std::uint8_t { Input, Image, Output };\n";
  emitFormats(h);
  h << "enum class ResourceId : std::uint32_t {\n";
  for (const auto& r : e.resources) h << "  " << r.name << ",\n";
  h << "};\nstruct ResourceInfo {\n  std::string_view name;\n  ResourceKind kind;\n  Format format;\n"
    << "  bool fullMipChain;          // mips=auto: as many levels as the plan needs\n"
    << "  bool inputExtent;           // true: the depth input's extent (viewport + guard band); false: the AO extent\n"
    << "  std::uint32_t scaleDenominator;  // extent = base extent / scaleDenominator\n"
    << "  std::int32_t whenVariant;   // exists only when this variant is non-zero; -1: always\n"
    << "  std::string_view doc;\n"
    << "  std::int32_t divideBy;  // a SettingId: the AO extent over that int setting, rounded up; -1: none\n"
    << "  // formats=: kind=output, every format it may have (empty: only `format`); a colour kind=input,\n"
    << "  // the formats it accepts (empty: any colour format with the channels the effect reads)\n"
    << "  std::span<const Format> formats;\n"
    << "  bool history;  // history=true: two images that trade places every frame; reads see the previous frame's\n"
    << "  std::int32_t formatWhenVariant;  // format_when=: where this variant is non-zero the image has formatWhen; -1: none\n"
    << "  Format formatWhen;\n};\n";
  for (const auto& r : e.resources) {
    if (r.formats.empty()) continue;
    h << "inline constexpr Format kFormats_" << r.name << "[] = {";
    for (size_t i = 0; i < r.formats.size(); ++i) h << (i ? ", " : "") << formatName(r.formats[i]);
    h << "};\n";
  }
  h
    << "inline constexpr std::array<ResourceInfo, " << e.resources.size() << "> kResources = {{\n";
  for (const auto& r : e.resources)
    h << "  {" << quoted(r.name) << ", " << kindName(r.kind) << ", " << formatName(r.format) << ", "
      << (r.fullMipChain ? "true" : "false") << ", " << (r.inputExtent ? "true" : "false") << ", " << r.scaleDenominator << ", " << r.whenVariant << ", "
      << quoted(r.doc) << ", " << r.divideBy << ", "
      << (r.formats.empty() ? std::string("{}") : "kFormats_" + r.name) << ", " << (r.history ? "true" : "false") << ", "
      << r.formatWhenVariant << ", " << formatName(r.formatWhen.empty() ? r.format : r.formatWhen) << "},\n";
  h << "}};\n\n";
  emitInputSet(h, e);

  // --- passes
  h << "// ---- Passes, in execution order, and their compiled variants.\n"
    << "enum class PassId : std::uint32_t {\n";
  for (const auto& p : e.passes) h << "  " << p.name << ",\n";
  h << "};\nstruct BindingInfo {\n  std::uint32_t binding;  // Vulkan set-0 binding\n"
    << "  ResourceId resource;\n  bool write;  // true: storage image out_<name>; false: sampler in_<name>\n"
    << "  Format format;  // the format the shader declares (a write's storage format)\n"
    << "  bool readWrite;  // a write the pass may also load from (a formats= output: kept channels, a multiply)\n"
    << "  std::uint32_t glUnit;  // GL texture unit (a read) or image unit (a write), each counted from 0\n"
    << "  std::uint32_t slots;  // array elements: a levels= pass's write of a MIP chain has one per level, else 1\n"
    << "  Format esFormat;  // a write's storage format on OpenGL ES 3.1 (the effect's `target gles` rule)\n"
    << "  std::int32_t esKeptUnit;  // GLES: the texture unit a readWrite write is loaded through; -1: the image itself\n};\n"
    << "struct PassVariantInfo {\n  VariantValues values;  // -1 where the pass does not depend on the variant\n"
    << "  std::span<const BindingInfo> bindings;\n  std::uint32_t glslBlob;\n  std::uint32_t spirvBlob;\n"
    << "  std::string_view fileStem;\n"
    << "  std::uint32_t sharedBytes;  // the work group's shared variables, tightly packed (from its SPIR-V)\n"
    << "  std::uint32_t pushConstantBytes;  // its push constants (PushConstants; Vulkan only), 0: none\n"
    << "  std::int32_t esslBlob;  // its GLSL ES 3.10 (esslSource); -1: the variant has no GLES form\n};\n"
    << "enum class Compare : std::uint8_t { Eq, Ne, Lt, Le, Gt, Ge };\n"
    << "// `setting op value` on a setting (pass rules: int or bool); never holds when not active.\n"
    << "struct SettingCondition {\n  bool active;\n  SettingId setting;\n  Compare op;\n  double value;\n};\n"
    << "bool holds(const SettingCondition& condition, const Settings& s);\n"
    << "// A binding of `declared` that `serving` fills instead (a skipped pass's output).\n"
    << "struct ResourceAlias {\n  ResourceId declared;\n  ResourceId serving;\n};\n"
    << "struct PassInfo {\n  std::string_view name;\n  std::string_view entry;\n  std::uint32_t localX, localY;\n"
    << "  std::uint32_t texelsX, texelsY;  // texels=WxH: an invocation covers WxH texels of the first written level\n"
    << "  // levels=A..B: one dispatch writes levels A..B of its chains (firstLevel A, levelSlots B - A + 1,\n"
    << "  // levels past the chain's last unwritten), reading level A - 1 of a chain it writes; 0 slots: not set\n"
    << "  std::uint32_t firstLevel;\n  std::uint32_t levelSlots;\n"
    << "  std::span<const ResourceId> reads;\n  std::span<const ResourceId> writes;\n"
    << "  std::span<const VariantId> variants;\n  std::span<const PassVariantInfo> compiled;\n"
    << "  SettingCondition skipWhen;   // the pass does not run when this holds\n"
    << "  SettingCondition aliasWhen;  // `aliases` apply when this holds\n"
    << "  std::span<const ResourceAlias> aliases;\n"
    << "  std::string_view doc;\n};\n"
    << "inline constexpr std::uint32_t kParamBlockBinding = 0;\n"
    << "std::span<const PassInfo> passes();\n"
    << "const PassInfo& pass(PassId id);\n"
    << "// The compiled variant of a pass for a full variant key, or nullptr if excluded.\n"
    << "const PassVariantInfo* findPassVariant(PassId id, const VariantValues& values);\n"
    << "std::string_view glslSource(std::uint32_t blob);        // GLSL 4.30 for OpenGL\n"
    << "std::span<const std::uint32_t> spirvModule(std::uint32_t blob);  // SPIR-V 1.3 for Vulkan 1.1+\n"
    << "// GLSL ES 3.10 for OpenGL ES 3.1, defined in " << e.name << "_effect_gles.cpp (linked by the GLES backend only)\n"
    << "std::string_view esslSource(std::uint32_t blob);\n"
    << "inline constexpr std::size_t kGlslBlobCount = " << glslBlobs.size() << ";\n"
    << "inline constexpr std::size_t kSpirvBlobCount = " << spirvBlobs.size() << ";\n"
    << "inline constexpr std::size_t kEsslBlobCount = " << esslBlobs.size() << ";\n\n";
  emitSettingRules(h, e);
  emitGlesRule(h, e);
  h << "}  // namespace sao::gen\n";

  // ================= source
  std::ostringstream s;
  s << "// Generated by sao-shaderc from the annotated effect '" << e.name << "'. Do not edit.\n"
    << "#include \"" << e.name << "_effect.h\"\n\n#include <algorithm>\n\nnamespace sao::gen {\n\n";
  s << "double settingValue(const Settings& s, SettingId id) {\n  switch (id) {\n";
  for (const auto& st : e.settings)
    s << "    case SettingId::" << st.name << ": return " << (st.type == ScalarType::Bool ? "s." + st.name + " ? 1.0 : 0.0" : "static_cast<double>(s." + st.name + ")") << ";\n";
  for (const auto& d : e.derived) {
    s << "    case SettingId::" << d.name << ": return (";
    for (size_t t = 0; t < d.terms.size(); ++t)
      s << (t ? " && " : "") << "holds(" << conditionValue(e, d.terms[t]) << ", s)";
    s << ") ? 1.0 : 0.0;\n";
  }
  s << "  }\n  return 0.0;\n}\n\n"
    << "void setSettingValue(Settings& s, SettingId id, double value) {\n  switch (id) {\n";
  for (const auto& st : e.settings) {
    s << "    case SettingId::" << st.name << ": s." << st.name << " = ";
    if (st.type == ScalarType::Float) s << "static_cast<float>(value)";
    else if (st.type == ScalarType::Int) s << "static_cast<std::int32_t>(value)";
    else s << "value != 0.0";
    s << "; return;\n";
  }
  for (const auto& d : e.derived) s << "    case SettingId::" << d.name << ": return;  // derived: computed\n";
  s << "  }\n}\n\n"
    << "std::string_view exclusionReason(const VariantValues& values) {\n"
    << "  for (const auto& x : kExclusions) {\n    bool all = true;\n"
    << "    for (std::size_t i = 0; i < kVariantCount; ++i)\n"
    << "      if (x.values[i] >= 0 && x.values[i] != values[i]) all = false;\n"
    << "    if (all) return x.reason;\n  }\n  return {};\n}\n\n"
    << "bool holds(const SettingCondition& c, const Settings& s) {\n"
    << "  if (!c.active) return false;\n  const double v = settingValue(s, c.setting);\n  switch (c.op) {\n"
    << "    case Compare::Eq: return v == c.value;\n    case Compare::Ne: return v != c.value;\n"
    << "    case Compare::Lt: return v < c.value;\n    case Compare::Le: return v <= c.value;\n"
    << "    case Compare::Gt: return v > c.value;\n    case Compare::Ge: return v >= c.value;\n"
    << "  }\n  return false;\n}\n\n";

  // bindings and variants per pass
  for (size_t p = 0; p < e.passes.size(); ++p) {
    const Pass& pass = e.passes[p];
    int k = 0;
    for (const auto& cpv : pvs) {
      if (cpv.variant.pass != static_cast<int>(p)) continue;
      const int index = k++;
      if (cpv.variant.bindings.empty()) continue;  // a variant that binds nothing (its resources absent): {} below
      s << "static constexpr BindingInfo kBindings_" << pass.name << "_" << index << "[] = {";
      for (const auto& bd : cpv.variant.bindings)
        s << "{" << bd.binding << ", ResourceId::" << e.resources[bd.resource].name << ", " << (bd.write ? "true" : "false")
          << ", " << formatName(bd.format) << ", " << (bd.readWrite ? "true" : "false") << ", " << bd.unit << ", "
          << bd.slots << ", " << formatName(bd.esFormat.empty() ? bd.format : bd.esFormat) << ", " << bd.esKeptUnit << "}, ";
      s << "};\n";
    }
    s << "static constexpr PassVariantInfo kCompiled_" << pass.name << "[] = {\n";
    k = 0;
    for (const auto& cpv : pvs) {
      if (cpv.variant.pass != static_cast<int>(p)) continue;
      s << "  {{";
      for (size_t i = 0; i < cpv.variant.values.size(); ++i) s << (i ? ", " : "") << cpv.variant.values[i];
      const int index = k++;
      s << "}, "
        << (cpv.variant.bindings.empty() ? std::string("{}") : "kBindings_" + pass.name + "_" + std::to_string(index))
        << ", " << cpv.glslBlob << ", " << cpv.spirvBlob << ", "
        << quoted(cpv.variant.stem) << ", " << cpv.facts.sharedBytes << ", " << cpv.facts.pushConstantBytes << ", "
        << cpv.esslBlob << "},\n";
    }
    s << "};\n";
    // Empty lists get no array (a zero-length array is an extension; kPasses names {} instead).
    auto list = [&](const char* type, const char* prefix, const std::vector<int>& ids, auto name) {
      if (ids.empty()) return;
      s << "static constexpr " << type << " " << prefix << pass.name << "[] = {";
      for (int id : ids) s << type << "::" << name(id) << ", ";
      s << "};\n";
    };
    list("ResourceId", "kReads_", pass.reads, [&](int r) { return e.resources[r].name; });
    list("ResourceId", "kWrites_", pass.writes, [&](int r) { return e.resources[r].name; });
    list("VariantId", "kVariants_", pass.variants, [&](int v) { return e.variants[v].name; });
    if (!pass.aliases.empty()) {
      s << "static constexpr ResourceAlias kAliases_" << pass.name << "[] = {";
      for (const auto& a : pass.aliases)
        s << "{ResourceId::" << e.resources[a.declared].name << ", ResourceId::" << e.resources[a.serving].name << "}, ";
      s << "};\n";
    }
    s << "\n";
  }
  s << "static constexpr PassInfo kPasses[] = {\n";
  for (const auto& pass : e.passes) {
    auto span = [&](const std::string& prefix, size_t n) {
      return n ? "std::span(" + prefix + pass.name + ")" : std::string("{}");
    };
    s << "  {" << quoted(pass.name) << ", " << quoted(pass.entry) << ", " << pass.localX << ", " << pass.localY << ", "
      << pass.texelsX << ", " << pass.texelsY << ", "
      << pass.firstLevel << ", " << pass.levelSlots << ", "
      << span("kReads_", pass.reads.size()) << ", "
      << span("kWrites_", pass.writes.size()) << ", " << span("kVariants_", pass.variants.size())
      << ", kCompiled_" << pass.name << ",\n   " << conditionValue(e, pass.skipWhen) << ", "
      << conditionValue(e, pass.aliasWhen) << ", " << span("kAliases_", pass.aliases.size()) << ", "
      << quoted(pass.doc) << "},\n";
  }
  s << "};\n\nstd::span<const PassInfo> passes() { return kPasses; }\n"
    << "const PassInfo& pass(PassId id) { return kPasses[static_cast<std::size_t>(id)]; }\n\n"
    << "const PassVariantInfo* findPassVariant(PassId id, const VariantValues& values) {\n"
    << "  if (!exclusionReason(values).empty()) return nullptr;\n"
    << "  for (const auto& c : pass(id).compiled) {\n    bool match = true;\n"
    << "    for (std::size_t i = 0; i < kVariantCount; ++i)\n"
    << "      if (c.values[i] >= 0 && c.values[i] != values[i]) match = false;\n"
    << "    if (match) return &c;\n  }\n  return nullptr;\n}\n\n";

  // blobs
  for (size_t i = 0; i < glslBlobs.size(); ++i)
    s << "static constexpr char kGlsl" << i << "[] =\n" << glslLiteral(glslBlobs[i]) << ";\n";
  s << "static constexpr std::string_view kGlsl[] = {";
  for (size_t i = 0; i < glslBlobs.size(); ++i) s << "{kGlsl" << i << ", sizeof kGlsl" << i << " - 1}, ";
  s << "};\n\n";
  for (size_t i = 0; i < spirvBlobs.size(); ++i) {
    s << "static constexpr std::uint32_t kSpirv" << i << "[] = {";
    for (size_t w = 0; w < spirvBlobs[i].size(); ++w) {
      if (w % 8 == 0) s << "\n  ";
      char buf[16];
      std::snprintf(buf, sizeof buf, "0x%08x,", spirvBlobs[i][w]);
      s << buf;
    }
    s << "\n};\n";
  }
  s << "static constexpr std::span<const std::uint32_t> kSpirv[] = {";
  for (size_t i = 0; i < spirvBlobs.size(); ++i) s << "kSpirv" << i << ", ";
  s << "};\n\n"
    << "std::string_view glslSource(std::uint32_t blob) { return blob < kGlslBlobCount ? kGlsl[blob] : std::string_view(); }\n"
    << "std::span<const std::uint32_t> spirvModule(std::uint32_t blob) {\n"
    << "  return blob < kSpirvBlobCount ? kSpirv[blob] : std::span<const std::uint32_t>();\n}\n\n"
    << "}  // namespace sao::gen\n";
  std::ostringstream es;
  es << "// Generated by sao-shaderc from effect '" << e.name << "': its GLSL ES 3.10. Do not edit.\n"
     << "#include \"" << e.name << "_effect.h\"\n\nnamespace sao::gen {\n\n";
  for (size_t i = 0; i < esslBlobs.size(); ++i)
    es << "static constexpr char kEssl" << i << "[] =\n" << glslLiteral(esslBlobs[i]) << ";\n";
  es << "static constexpr std::string_view kEssl[] = {";
  for (size_t i = 0; i < esslBlobs.size(); ++i) es << "{kEssl" << i << ", sizeof kEssl" << i << " - 1}, ";
  es << "{}};\n\nstd::string_view esslSource(std::uint32_t blob) { return blob < " << esslBlobs.size()
     << " ? kEssl[blob] : std::string_view(); }\n\n}  // namespace sao::gen\n";
  return {h.str(), s.str(), es.str()};
}

}  // namespace sao::codegen
