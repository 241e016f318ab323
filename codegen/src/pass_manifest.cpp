#include "pass_manifest.h"

#include <cstdio>
#include <sstream>

#include "cross_targets.h"

namespace sao::codegen {
namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

const char* kindName(ResourceKind k) {
  switch (k) {
    case ResourceKind::Input: return "input";
    case ResourceKind::Image: return "image";
    case ResourceKind::Output: return "output";
  }
  return "?";
}

std::string condition(const std::optional<SettingCondition>& c) { return c ? quoted(c->text) : "null"; }

}  // namespace

std::string passesJson(const Effect& e, const std::vector<CompiledPassVariant>& compiled) {
  std::ostringstream j;
  j << "{\n  \"effect\": " << quoted(e.name) << ",\n  \"version\": " << e.version << ",\n";

  const ParamBlock& b = *e.block;
  j << "  \"parameter_block\": {\"name\": " << quoted(b.name) << ", \"layout\": \"std140\", \"vulkan_binding\": 0, "
    << "\"gl_uniform_binding\": 0, \"bytes\": " << b.size << ", \"members\": [";
  for (std::size_t i = 0; i < b.members.size(); ++i) {
    const BlockMember& m = b.members[i];
    j << (i ? "," : "") << "\n    {\"name\": " << quoted(m.name) << ", \"type\": " << quoted(m.glslType)
      << ", \"offset\": " << m.offset << ", \"array\": " << m.arraySize << "}";
  }
  j << "]},\n";

  const SpirvFacts* push = pushConstantFacts(compiled);
  j << "  \"push_constants\": ";
  if (!push) {
    j << "null,\n";
  } else {
    j << "{\"name\": " << quoted(push->pushConstantBlock) << ", \"bytes\": " << push->pushConstantBytes
      << ", \"members\": [";
    for (std::size_t i = 0; i < push->pushConstants.size(); ++i) {
      const PushConstantMember& m = push->pushConstants[i];
      j << (i ? ", " : "") << "{\"name\": " << quoted(m.name) << ", \"type\": " << quoted(m.glslType)
        << ", \"offset\": " << m.offset << ", \"from_parameter_block\": " << quoted(m.name) << "}";
    }
    j << "]},\n";
  }

  // Per target: HLSL's cbuffer registers; GLES's storage formats and refusals (the effect's rule).
  j << "  \"targets\": {\"hlsl\": {\"shader_models\": [\"5.0\", \"6.0\"], \"parameter_block\": \"b" << kHlslParamsRegister
    << "\", \"push_constants\": \"b" << kHlslPushRegister << "\", \"entry_point\": \"main\"}, \"gles\": {\"version\": \"3.10\", \"storage\": {";
  if (e.gles)
    for (std::size_t i = 0; i < e.gles->storage.size(); ++i)
      j << (i ? ", " : "") << quoted(e.gles->storage[i].from) << ": " << quoted(e.gles->storage[i].to);
  j << "}, \"refused\": [";
  if (e.gles)
    for (std::size_t i = 0; i < e.gles->refused.size(); ++i) j << (i ? ", " : "") << quoted(e.gles->refused[i]);
  j << "]}},\n";

  j << "  \"variants\": [";
  for (std::size_t i = 0; i < e.variants.size(); ++i)
    j << (i ? ", " : "") << quoted(e.variants[i].name);
  j << "],\n  \"resources\": [";
  for (std::size_t i = 0; i < e.resources.size(); ++i) {
    const Resource& r = e.resources[i];
    j << (i ? "," : "") << "\n    {\"name\": " << quoted(r.name) << ", \"kind\": \"" << kindName(r.kind)
      << "\", \"format\": " << quoted(r.format) << ", \"mip_chain\": " << (r.fullMipChain ? "true" : "false")
      << ", \"history\": " << (r.history ? "true" : "false") << "}";
  }
  j << "],\n  \"passes\": [";
  for (std::size_t p = 0; p < e.passes.size(); ++p) {
    const Pass& pass = e.passes[p];
    j << (p ? "," : "") << "\n    {\"name\": " << quoted(pass.name) << ", \"local_size\": [" << pass.localX << ", "
      << pass.localY << "], \"texels\": [" << pass.texelsX << ", " << pass.texelsY << "], \"levels\": ";
    if (pass.levelSlots) j << "[" << pass.firstLevel << ", " << pass.firstLevel + pass.levelSlots - 1 << "]";
    else j << "null";
    j << ", \"skip_when\": " << condition(pass.skipWhen) << ", \"alias_when\": " << condition(pass.aliasWhen)
      << ", \"aliases\": [";
    for (std::size_t a = 0; a < pass.aliases.size(); ++a)
      j << (a ? ", " : "") << "{\"declared\": " << quoted(e.resources[pass.aliases[a].declared].name)
        << ", \"serving\": " << quoted(e.resources[pass.aliases[a].serving].name) << "}";
    j << "], \"compiled\": [";
    bool first = true;
    for (const auto& c : compiled) {
      if (c.variant.pass != static_cast<int>(p)) continue;
      j << (first ? "" : ",") << "\n      {\"variant_values\": {";
      bool firstValue = true;
      for (std::size_t v = 0; v < c.variant.values.size(); ++v) {
        if (c.variant.values[v] < 0) continue;  // the pass does not depend on it
        j << (firstValue ? "" : ", ") << quoted(e.variants[v].name) << ": " << c.variant.values[v];
        firstValue = false;
      }
      j << "}, \"glsl\": " << quoted(c.variant.stem + ".glsl") << ", \"spirv\": " << quoted(c.variant.stem + ".spv")
        << ", \"hlsl_sm50\": " << quoted(c.variant.stem + ".sm50.hlsl") << ", \"hlsl_sm60\": " << quoted(c.variant.stem + ".sm60.hlsl")
        << ", \"essl\": " << (c.esslBlob >= 0 ? quoted(c.variant.stem + ".es310.glsl") : std::string("null"))
        << ", \"shared_bytes\": " << c.facts.sharedBytes << ", \"push_constant_bytes\": " << c.facts.pushConstantBytes
        << ", \"bindings\": [";
      const auto registers = hlslRegisters(c.variant);
      for (std::size_t k = 0; k < c.variant.bindings.size(); ++k) {
        const Binding& bd = c.variant.bindings[k];
        const std::string reg = std::to_string(registers[k].index);
        j << (k ? "," : "") << "\n        {\"vulkan_binding\": " << bd.binding << ", \"gl_unit\": " << bd.unit
          << ", \"resource\": " << quoted(e.resources[bd.resource].name) << ", \"access\": \""
          << (bd.write ? (bd.readWrite ? "read_write" : "write") : "read") << "\", \"format\": " << quoted(bd.format)
          << ", \"slots\": " << bd.slots << ", \"multisampled\": " << (bd.multisampled ? "true" : "false")
          << ", \"hlsl\": " << (bd.write ? "{\"uav\": \"u" + reg + "\"}" : "{\"srv\": \"t" + reg + "\", \"sampler\": \"s" + reg + "\"}");
        if (bd.write && c.esslBlob >= 0)
          j << ", \"gles\": {\"format\": " << quoted(bd.esFormat) << ", \"kept_texture_unit\": "
            << (bd.esKeptUnit >= 0 ? std::to_string(bd.esKeptUnit) : std::string("null")) << "}";
        j << "}";
      }
      j << "]}";
      first = false;
    }
    j << "]}";
  }
  j << "]\n}\n";
  return j.str();
}

}  // namespace sao::codegen
