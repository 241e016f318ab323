// sao-shaderc: compiles an annotated SAO effect into GLSL 4.30, SPIR-V and C++ glue.
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "cpp_emitter.h"
#include "diagnostics.h"
#include "directive_parser.h"
#include "output_writer.h"
#include "pass_manifest.h"
#include "pass_builder.h"
#include "shader_compiler.h"
#include "source_loader.h"
#include "target_sources.h"

namespace {

using namespace sao::codegen;

constexpr const char* kUsage =
    "usage: sao-shaderc <effect.glsl> -o <dir> [--depfile <file>] [--overwrite] [--spirv-from-hlsl 50|60]\n"
    "  Writes <name>_effect.h, <name>_effect.cpp (C++ glue with embedded shaders), <name>_passes.json\n"
    "  (the pass description) and for every pass and variant <stem>.glsl (GLSL 4.30, OpenGL),\n"
    "  <stem>.spv (SPIR-V 1.3, Vulkan 1.1), <stem>.sm50.hlsl and <stem>.sm60.hlsl (HLSL, shader models\n"
    "  5.0 and 6.0) and, where the variant exists on OpenGL ES 3.1, <stem>.es310.glsl (GLSL ES 3.10),\n"
    "  and lists them in <dir>/sao-shaderc-outputs.txt. A file of the same name that sao-shaderc did not\n"
    "  write (not listed there) is replaced only with --overwrite; an input never.\n"
    "  --spirv-from-hlsl: the .spv files and the C++ glue hold, instead of the SPIR-V compiled from GLSL,\n"
    "  the SPIR-V that glslang's HLSL front end compiles from that shader model's HLSL (the HLSL round\n"
    "  trip's test).\n";

std::string spirvBytes(const std::vector<uint32_t>& words) {
  std::string out(words.size() * 4, '\0');
  for (size_t i = 0; i < words.size(); ++i)
    for (int b = 0; b < 4; ++b) out[i * 4 + b] = static_cast<char>((words[i] >> (8 * b)) & 0xffu);  // little endian
  return out;
}

// A pass's skip/alias rules as the source spells them, for the pass table in words.
std::string rulesText(const Effect& e, const Pass& p) {
  std::string out;
  if (p.skipWhen) out += " skip_when=" + p.skipWhen->text;
  if (p.aliasWhen) {
    out += " alias_when=" + p.aliasWhen->text + ":";
    for (size_t i = 0; i < p.aliases.size(); ++i)
      out += (i ? "," : "") + e.resources[p.aliases[i].declared].name + "=" + e.resources[p.aliases[i].serving].name;
  }
  return out;
}

// One push-constant block for every pass that declares one, its members 32-bit scalars packed from
// offset 0 (so that gen::PushConstants mirrors it) and each the parameter block's member of the
// same name and type (so that gen::pushConstantsOf fills it).
void checkPushConstants(const Effect& e, const std::vector<CompiledPassVariant>& compiled, Diagnostics& diags) {
  const CompiledPassVariant* first = nullptr;
  for (const auto& c : compiled) {
    if (c.facts.pushConstantBytes == 0) continue;
    const SourceLoc& loc = e.passes[c.variant.pass].loc;
    if (!first) {
      first = &c;
      for (std::size_t i = 0; i < c.facts.pushConstants.size(); ++i) {
        const PushConstantMember& m = c.facts.pushConstants[i];
        if (m.offset != 4 * i)
          diags.error(loc, "push constant '" + m.name + "' of " + c.facts.pushConstantBlock + " is at offset " +
                               std::to_string(m.offset) + "; members must be packed from 0 (offset " +
                               std::to_string(4 * i) + ")");
        const auto match = std::find_if(e.block->members.begin(), e.block->members.end(), [&](const BlockMember& b) {
          return b.name == m.name && b.glslType == m.glslType && b.arraySize == 0;
        });
        if (match == e.block->members.end())
          diags.error(loc, "push constant '" + m.name + "' (" + m.glslType + ") of " + c.facts.pushConstantBlock +
                               " has no member of the same name and type in the parameter block " + e.block->name);
      }
      continue;
    }
    bool same = c.facts.pushConstantBlock == first->facts.pushConstantBlock &&
                c.facts.pushConstants.size() == first->facts.pushConstants.size();
    for (std::size_t i = 0; same && i < c.facts.pushConstants.size(); ++i)
      same = c.facts.pushConstants[i].name == first->facts.pushConstants[i].name &&
             c.facts.pushConstants[i].glslType == first->facts.pushConstants[i].glslType;
    if (!same)
      diags.error(loc, "pass variant " + c.variant.stem + " declares push-constant block " + c.facts.pushConstantBlock +
                           " unlike " + first->variant.stem + "'s " + first->facts.pushConstantBlock +
                           ": every pass that takes push constants must declare the same block");
  }
}

// One pass variant's outputs: its GLSL, its SPIR-V (the HLSL round trip's with --spirv-from-hlsl),
// HLSL and GLSL ES, each checked; ok false (with diags) when any step failed.
struct VariantResult {
  bool ok = false;
  Diagnostics diags;
  CompiledPassVariant compiled;
  std::string glsl, hlsl50, hlsl60, essl;
  std::vector<uint32_t> spirv;
};

VariantResult compileVariant(const Effect& effect, const PassVariant& pv, int spirvFromHlsl) {
  VariantResult r;
  Diagnostics& diags = r.diags;
  const SourceLoc& passLoc = effect.passes[pv.pass].loc;
  const auto glShader = composeShader(effect, pv, Target::OpenGL);
  const bool glOk = checkOpenGl(glShader, passLoc, &*effect.block, diags);
  const bool vkOk = compileVulkan(composeShader(effect, pv, Target::Vulkan), passLoc, r.spirv, diags);
  if (!glOk || !vkOk) return r;
  r.glsl = joinLines(glShader);
  r.compiled = CompiledPassVariant{pv, 0, 0, {}, -1};
  if (std::string why; !readSpirvFacts(r.spirv, r.compiled.facts, why)) {
    diags.error(passLoc, "pass variant " + pv.stem + ": its SPIR-V cannot be read for shared memory and push constants: " + why);
    return r;
  }
  const std::string& push = r.compiled.facts.pushConstantBlock;
  std::vector<uint32_t> roundTrip50, roundTrip60;
  if (!hlslOf(effect, r.spirv, pv, 50, push, spirvFromHlsl == 50, passLoc, r.hlsl50, roundTrip50, diags) ||
      !hlslOf(effect, r.spirv, pv, 60, push, spirvFromHlsl == 60, passLoc, r.hlsl60, roundTrip60, diags) ||
      (pv.onGles && !esslOf(effect, pv, passLoc, r.essl, diags)))
    return r;
  if (spirvFromHlsl) r.spirv = spirvFromHlsl == 50 ? roundTrip50 : roundTrip60;
  r.ok = true;
  return r;
}

int fail(const Diagnostics& diags) {
  for (const auto& d : diags.all()) std::fprintf(stderr, "%s\n", d.format().c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  std::string input, outDir, depfile;
  WriteRules rules;
  int spirvFromHlsl = 0;  // 50 or 60: embed the HLSL round trip's SPIR-V
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "-o" || a == "--depfile") && i + 1 < argc) (a == "-o" ? outDir : depfile) = argv[++i];
    else if (a == "--overwrite") rules.overwrite = true;
    else if (a == "--spirv-from-hlsl" && i + 1 < argc && (std::string(argv[i + 1]) == "50" || std::string(argv[i + 1]) == "60"))
      spirvFromHlsl = std::stoi(argv[++i]);
    else if (a == "-h" || a == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (!a.empty() && a[0] != '-' && input.empty()) input = a;
    else {
      std::fprintf(stderr, "sao-shaderc: error: unexpected argument '%s'\n%s", a.c_str(), kUsage);
      return 2;
    }
  }
  if (input.empty() || outDir.empty()) {
    std::fprintf(stderr, "sao-shaderc: error: need an effect file and -o <dir>\n%s", kUsage);
    return 2;
  }

  Diagnostics diags;
  const LoadedSource source = loadSource(input, diags);
  if (diags.hasErrors()) return fail(diags);
  const Effect effect = parseEffect(source, diags);
  if (diags.hasErrors()) return fail(diags);

  GlslangProcess glslang;
  OutputSet outputs;
  std::vector<CompiledPassVariant> compiled;
  std::vector<std::string> glslBlobs, esslBlobs;
  std::vector<std::vector<uint32_t>> spirvBlobs;
  std::map<std::string, int> glslIndex, esslIndex;
  std::map<std::vector<uint32_t>, int> spirvIndex;
  // The variants compiled by one thread per core (each variant its own glslang, SPIRV-Tools and
  // SPIRV-Cross objects; the effect is read only), then merged in variant order: the outputs and
  // their blob numbering do not depend on the threads.
  const std::vector<PassVariant> variants = buildPassVariants(effect);
  std::vector<VariantResult> results(variants.size());
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t i; (i = next++) < variants.size();) results[i] = compileVariant(effect, variants[i], spirvFromHlsl);
  };
  std::vector<std::thread> threads(std::clamp(std::thread::hardware_concurrency(), 1u, 16u) - 1);
  for (auto& t : threads) t = std::thread(work);
  work();
  for (auto& t : threads) t.join();
  for (VariantResult& r : results) {
    diags.append(r.diags);
    if (!r.ok) continue;
    CompiledPassVariant& c = r.compiled;
    const std::string& stem = c.variant.stem;
    outputs.add(stem + ".glsl", r.glsl);
    outputs.add(stem + ".sm50.hlsl", r.hlsl50);
    outputs.add(stem + ".sm60.hlsl", r.hlsl60);
    if (c.variant.onGles) {
      outputs.add(stem + ".es310.glsl", r.essl);
      c.esslBlob = esslIndex.emplace(r.essl, static_cast<int>(esslBlobs.size())).first->second;
      if (c.esslBlob == static_cast<int>(esslBlobs.size())) esslBlobs.push_back(r.essl);
    }
    outputs.add(stem + ".spv", spirvBytes(r.spirv));
    c.glslBlob = glslIndex.emplace(r.glsl, static_cast<int>(glslBlobs.size())).first->second;
    if (c.glslBlob == static_cast<int>(glslBlobs.size())) glslBlobs.push_back(r.glsl);
    c.spirvBlob = spirvIndex.emplace(r.spirv, static_cast<int>(spirvBlobs.size())).first->second;
    if (c.spirvBlob == static_cast<int>(spirvBlobs.size())) spirvBlobs.push_back(r.spirv);
    compiled.push_back(c);
  }
  checkPushConstants(effect, compiled, diags);
  if (diags.hasErrors()) return fail(diags);

  const GeneratedCode code = emitCpp(effect, compiled, glslBlobs, spirvBlobs, esslBlobs);
  const std::string headerName = effect.name + "_effect.h";
  outputs.add(headerName, code.header);
  outputs.add(effect.name + "_effect.cpp", code.source);
  outputs.add(effect.name + "_effect_gles.cpp", code.glesSource);
  // The pass table in words (one line per compiled pass variant): what the generated tables say,
  // readable in a diff and kept as a golden file by the tests.
  std::string manifest;
  for (const auto& c : compiled) {
    const Pass& pass = effect.passes[c.variant.pass];
    manifest += c.variant.stem + " local=" + std::to_string(pass.localX) + "x" + std::to_string(pass.localY) +
                (pass.texelsX * pass.texelsY > 1
                     ? " texels=" + std::to_string(pass.texelsX) + "x" + std::to_string(pass.texelsY)
                     : "") +
                (pass.levelSlots ? " levels=" + std::to_string(pass.firstLevel) + ".." +
                                       std::to_string(pass.firstLevel + pass.levelSlots - 1)
                                 : "") +
                rulesText(effect, pass) +
                (c.facts.sharedBytes ? " shared=" + std::to_string(c.facts.sharedBytes) : "") +
                (c.facts.pushConstantBytes ? " push=" + std::to_string(c.facts.pushConstantBytes) : "") +
                " glsl=#" + std::to_string(c.glslBlob) + " spirv=#" +
                std::to_string(c.spirvBlob) + " | 0 block " + effect.block->name;
    for (const auto& b : c.variant.bindings) {
      const Resource& r = effect.resources[b.resource];
      manifest += ", " + std::to_string(b.binding) + (b.write ? " out " : " in ") + r.name +
                  (b.slots > 1 ? "[" + std::to_string(b.slots) + "]" : "") + " " + b.format + (b.readWrite ? " rw" : "") +
                  " gl" + (b.write ? " image " : " texture ") + std::to_string(b.unit);
    }
    manifest += "\n";
  }
  outputs.add(effect.name + "_passes.txt", manifest);
  outputs.add(effect.name + "_passes.json", passesJson(effect, compiled));
  for (const auto& d : diags.all()) std::fprintf(stderr, "%s\n", d.format().c_str());  // warnings
  rules.inputs = source.files;
  if (const std::string err = outputs.commit(outDir, rules); !err.empty()) {
    std::fprintf(stderr, "sao-shaderc: error: %s\n", err.c_str());
    return 1;
  }
  if (!depfile.empty()) {
    // Written last, only on success. Paths here are the build's business; the generated sources hold none.
    OutputSet dep;
    const std::filesystem::path depPath(depfile);
    dep.add(depPath.filename().string(), makeDepfile((std::filesystem::path(outDir) / headerName).string(), source.files));
    const std::string depDir = depPath.parent_path().empty() ? "." : depPath.parent_path().string();
    if (const std::string err = dep.commit(depDir, rules); !err.empty()) {
      std::fprintf(stderr, "sao-shaderc: error: %s\n", err.c_str());
      return 1;
    }
  }
  return 0;
}
