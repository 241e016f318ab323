#include "spirv_facts.h"

#include <algorithm>
#include <map>

namespace sao::codegen {
namespace {

// The few opcodes, storage classes and decorations read here (SPIR-V 1.3 specification).
enum : std::uint32_t {
  OpName = 5, OpMemberName = 6, OpTypeBool = 20, OpTypeInt = 21, OpTypeFloat = 22, OpTypeVector = 23,
  OpTypeMatrix = 24, OpTypeArray = 28, OpTypeStruct = 30, OpTypePointer = 32, OpConstant = 43,
  OpVariable = 59, OpMemberDecorate = 72,
};
enum : std::uint32_t { StorageWorkgroup = 4, StoragePushConstant = 9 };
enum : std::uint32_t { DecorationOffset = 35 };

std::string literalString(const std::uint32_t* words, std::size_t count) {
  std::string s;
  for (std::size_t i = 0; i < count; ++i)
    for (int b = 0; b < 4; ++b) {
      const char c = static_cast<char>((words[i] >> (8 * b)) & 0xff);
      if (c == '\0') return s;
      s += c;
    }
  return s;
}

struct Module {
  std::map<std::uint32_t, std::vector<std::uint32_t>> types;  // id -> the instruction's words
  std::map<std::uint32_t, std::uint32_t> constants;           // id -> its 32-bit value
  std::map<std::uint32_t, std::string> names;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::string> memberNames;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> memberOffsets;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> variables;  // (pointer type, storage class)
};

// Tightly packed size of type `id`; 0 (and `error`) when it cannot be sized.
std::uint32_t sizeOf(const Module& m, std::uint32_t id, std::string& error) {
  const auto it = m.types.find(id);
  if (it == m.types.end()) {
    error = "type %" + std::to_string(id) + " is not a type this reader sizes";
    return 0;
  }
  const std::vector<std::uint32_t>& t = it->second;
  switch (t[0] & 0xffff) {
    case OpTypeBool: return 4;
    case OpTypeInt:
    case OpTypeFloat: return t[2] / 8;
    case OpTypeVector:
    case OpTypeMatrix: return t[3] * sizeOf(m, t[2], error);
    case OpTypeArray: {
      const auto length = m.constants.find(t[3]);
      if (length == m.constants.end()) {
        error = "an array's length is not a constant";
        return 0;
      }
      return length->second * sizeOf(m, t[2], error);
    }
    case OpTypeStruct: {
      std::uint32_t total = 0;
      for (std::size_t i = 2; i < t.size(); ++i) total += sizeOf(m, t[i], error);
      return total;
    }
    default: error = "type %" + std::to_string(id) + " has an opcode this reader does not size"; return 0;
  }
}

std::string scalarName(const Module& m, std::uint32_t id) {
  const auto it = m.types.find(id);
  if (it == m.types.end()) return {};
  const std::vector<std::uint32_t>& t = it->second;
  if ((t[0] & 0xffff) == OpTypeInt && t[2] == 32) return t[3] ? "int" : "uint";
  if ((t[0] & 0xffff) == OpTypeFloat && t[2] == 32) return "float";
  return {};
}

}  // namespace

bool readSpirvFacts(const std::vector<std::uint32_t>& spirv, SpirvFacts& out, std::string& error) {
  out = SpirvFacts{};
  if (spirv.size() < 5) {
    error = "the module is shorter than its header";
    return false;
  }
  Module m;
  for (std::size_t at = 5; at < spirv.size();) {
    const std::uint32_t count = spirv[at] >> 16, op = spirv[at] & 0xffff;
    if (count == 0 || at + count > spirv.size()) {
      error = "an instruction runs past the module's end";
      return false;
    }
    const std::uint32_t* w = &spirv[at];
    switch (op) {
      case OpName: m.names[w[1]] = literalString(w + 2, count - 2); break;
      case OpMemberName: m.memberNames[{w[1], w[2]}] = literalString(w + 3, count - 3); break;
      case OpMemberDecorate:
        if (count >= 5 && w[3] == DecorationOffset) m.memberOffsets[{w[1], w[2]}] = w[4];
        break;
      case OpTypeBool: case OpTypeInt: case OpTypeFloat: case OpTypeVector: case OpTypeMatrix:
      case OpTypeArray: case OpTypeStruct: case OpTypePointer:
        m.types[w[1]].assign(w, w + count);
        break;
      case OpConstant:
        if (count == 4) m.constants[w[2]] = w[3];
        break;
      case OpVariable: m.variables.push_back({w[1], w[3]}); break;
      default: break;
    }
    at += count;
  }
  for (const auto& [pointer, storage] : m.variables) {
    if (storage != StorageWorkgroup && storage != StoragePushConstant) continue;
    const auto p = m.types.find(pointer);  // a variable's type is a pointer
    if (p == m.types.end() || (p->second[0] & 0xffff) != OpTypePointer) {
      error = "a variable's type is not a pointer";
      return false;
    }
    const std::uint32_t pointee = p->second[3];
    if (storage == StorageWorkgroup) {
      out.sharedBytes += sizeOf(m, pointee, error);
      if (!error.empty()) return false;
      continue;
    }
    if (!out.pushConstantBlock.empty()) {
      error = "more than one push-constant block";
      return false;
    }
    const auto type = m.types.find(pointee);
    out.pushConstantBlock = m.names.count(pointee) ? m.names.at(pointee) : std::string();
    if (out.pushConstantBlock.empty() || type == m.types.end() || (type->second[0] & 0xffff) != OpTypeStruct) {
      error = "the push-constant block has no name or is not a struct";
      return false;
    }
    const std::vector<std::uint32_t>& block = type->second;
    for (std::uint32_t i = 0; i + 2 < block.size(); ++i) {
      PushConstantMember member;
      member.glslType = scalarName(m, block[i + 2]);
      const auto name = m.memberNames.find({pointee, i});
      const auto offset = m.memberOffsets.find({pointee, i});
      if (name == m.memberNames.end() || offset == m.memberOffsets.end() || member.glslType.empty()) {
        error = "push-constant member " + std::to_string(i) + " of " + out.pushConstantBlock +
                " is not a named 32-bit int, uint or float with an offset";
        return false;
      }
      member.name = name->second;
      member.offset = offset->second;
      out.pushConstantBytes = std::max(out.pushConstantBytes, member.offset + 4);
      out.pushConstants.push_back(member);
    }
  }
  return true;
}

}  // namespace sao::codegen
