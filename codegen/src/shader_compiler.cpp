#include "shader_compiler.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <spirv-tools/libspirv.hpp>
#include <spirv-tools/optimizer.hpp>

#include <functional>
#include <memory>
#include <regex>
#include <sstream>

#include "pass_builder.h"

namespace sao::codegen {
namespace {

// glslang's log lines: "ERROR: 0:12: 'x' : undeclared identifier".
void reportLog(const std::string& log, const std::vector<SourceLine>& shader, const SourceLoc& passLoc,
               Diagnostics& diags) {
  static const std::regex located(R"(^(ERROR|WARNING): [^:]*:(\d+): (.*)$)");
  static const std::regex plain(R"(^(ERROR|WARNING): (.*)$)");
  std::istringstream in(log);
  std::string line;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_match(line, m, located)) {
      const size_t n = std::stoul(m[2].str());
      const SourceLoc loc = n >= 1 && n <= shader.size() ? shader[n - 1].loc : passLoc;
      if (m[1] == "ERROR") diags.error(loc, m[3].str());
      else diags.warning(loc, m[3].str());
    } else if (std::regex_match(line, m, plain)) {
      const std::string msg = m[2].str();
      if (msg.find("compilation errors") != std::string::npos) continue;  // summary line
      if (m[1] == "ERROR") diags.error(passLoc, msg);
      else diags.warning(passLoc, msg);
    }
  }
}

struct Compiled {
  std::unique_ptr<glslang::TShader> shader;
  std::unique_ptr<glslang::TProgram> program;
};

// The front ends sao-shaderc drives: GLSL for OpenGL (no SPIR-V), GLSL to SPIR-V for Vulkan or for
// OpenGL (the GLES path's input), GLSL ES 3.10 (a check), HLSL to SPIR-V for Vulkan (a check).
enum class FrontEnd { OpenGl, Vulkan, OpenGlSpirv, Es310, HlslVulkan };

// Register classes (HLSL) move to their own binding ranges, so that the SPIR-V's bindings say which
// register each came from (hlslVulkanBinding undoes it).
constexpr unsigned kUavShift = 100, kTextureShift = 200, kSamplerShift = 300, kCbufferShift = 400;

bool parseAndLink(const std::vector<SourceLine>& lines, const SourceLoc& passLoc, FrontEnd fe, Compiled& c,
                  Diagnostics& diags) {
  const std::string text = joinLines(lines);
  const char* str = text.c_str();
  c.shader = std::make_unique<glslang::TShader>(EShLangCompute);
  c.shader->setStrings(&str, 1);
  EShMessages messages = EShMsgDefault;
  int version = 430;
  EProfile profile = ENoProfile;
  switch (fe) {
    case FrontEnd::Vulkan:
    case FrontEnd::HlslVulkan:
      c.shader->setEnvInput(fe == FrontEnd::Vulkan ? glslang::EShSourceGlsl : glslang::EShSourceHlsl, EShLangCompute,
                            glslang::EShClientVulkan, 100);
      c.shader->setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_1);
      c.shader->setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_3);
      messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
      version = 450;
      if (fe == FrontEnd::HlslVulkan) {
        messages = static_cast<EShMessages>(messages | EShMsgReadHlsl);
        version = 100;
        c.shader->setEntryPoint("main");
        c.shader->setHlslIoMapping(true);
        c.shader->setAutoMapBindings(false);
        c.shader->setTextureSamplerTransformMode(EShTexSampTransUpgradeTextureRemoveSampler);
        c.shader->setShiftBinding(glslang::EResUav, kUavShift);
        c.shader->setShiftBinding(glslang::EResTexture, kTextureShift);
        c.shader->setShiftBinding(glslang::EResSampler, kSamplerShift);
        c.shader->setShiftBinding(glslang::EResUbo, kCbufferShift);
      }
      break;
    case FrontEnd::OpenGlSpirv:
      c.shader->setEnvInput(glslang::EShSourceGlsl, EShLangCompute, glslang::EShClientOpenGL, 100);
      c.shader->setEnvClient(glslang::EShClientOpenGL, glslang::EShTargetOpenGL_450);
      c.shader->setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_0);
      messages = EShMsgSpvRules;
      break;
    case FrontEnd::Es310:
      version = 310;
      profile = EEsProfile;
      [[fallthrough]];
    case FrontEnd::OpenGl:
      c.shader->setEnvInput(glslang::EShSourceGlsl, EShLangCompute, glslang::EShClientNone, 0);
      break;
  }
  if (!c.shader->parse(GetDefaultResources(), version, profile, false, false, messages)) {
    reportLog(c.shader->getInfoLog(), lines, passLoc, diags);
    return false;
  }
  reportLog(c.shader->getInfoLog(), lines, passLoc, diags);  // warnings
  c.program = std::make_unique<glslang::TProgram>();
  c.program->addShader(c.shader.get());
  if (!c.program->link(messages) || (fe == FrontEnd::HlslVulkan && !c.program->mapIO())) {
    reportLog(c.program->getInfoLog(), lines, passLoc, diags);
    return false;
  }
  return true;
}

// Generated text (ESSL, HLSL) as lines that all map to the pass.
std::vector<SourceLine> textLines(const std::string& text, const SourceLoc& passLoc) {
  std::vector<SourceLine> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back({line, passLoc});
  return lines;
}

std::string spvMessage(const char* message, const spv_position_t& pos) {
  return std::string(message) + " (SPIR-V word " + std::to_string(pos.index) + ")";
}

}  // namespace

GlslangProcess::GlslangProcess() { glslang::InitializeProcess(); }
GlslangProcess::~GlslangProcess() { glslang::FinalizeProcess(); }

bool checkOpenGl(const std::vector<SourceLine>& shader, const SourceLoc& passLoc, const ParamBlock* block,
                 Diagnostics& diags) {
  Compiled c;
  if (!parseAndLink(shader, passLoc, FrontEnd::OpenGl, c, diags)) return false;
  if (!block) return true;
  c.program->buildReflection(EShReflectionAllBlockVariables);
  bool ok = true;
  for (int i = 0; i < c.program->getNumUniformVariables(); ++i) {
    const glslang::TObjectReflection& u = c.program->getUniform(i);
    for (const auto& m : block->members) {
      std::string name = u.name;
      if (const auto dot = name.rfind('.'); dot != std::string::npos) name = name.substr(dot + 1);
      if (const auto br = name.find('['); br != std::string::npos) name = name.substr(0, br);
      if (name != m.name || u.offset < 0) continue;
      if (u.offset != m.offset) {
        diags.error(m.loc, "internal: glslang places block member '" + m.name + "' at offset " +
                               std::to_string(u.offset) + ", sao-shaderc at " + std::to_string(m.offset));
        ok = false;
      }
    }
  }
  return ok;
}

namespace {

// SPIR-V of a linked program, validated, optimised (spirv-opt's performance passes) and validated again.
// optimise false: validated only (a check whose module is not kept).
bool toSpirv(Compiled& c, const SourceLoc& passLoc, spv_target_env env, std::vector<uint32_t>& spirv, Diagnostics& diags,
             const std::function<void(std::vector<uint32_t>&)>& rewrite = {}, bool optimise = true) {
  std::vector<uint32_t> raw;
  glslang::SpvOptions options;
  options.disableOptimizer = true;  // spirv-opt below, with validation before and after
  options.validate = false;
  spv::SpvBuildLogger logger;
  glslang::GlslangToSpv(*c.program->getIntermediate(EShLangCompute), raw, &logger, &options);
  if (!logger.getAllMessages().empty()) diags.warning(passLoc, "glslang SPIR-V: " + logger.getAllMessages());
  if (rewrite) rewrite(raw);

  bool ok = true;
  auto consumer = [&](spv_message_level_t level, const char*, const spv_position_t& pos, const char* message) {
    if (level <= SPV_MSG_ERROR) {
      diags.error(passLoc, "spirv-val: " + spvMessage(message, pos));
      ok = false;
    }
  };
  spvtools::SpirvTools tools(env);
  tools.SetMessageConsumer(consumer);
  if (!tools.Validate(raw)) return false;
  if (!optimise) {
    spirv = std::move(raw);
    return ok;
  }

  spvtools::Optimizer optimizer(env);
  optimizer.SetMessageConsumer(consumer);
  optimizer.RegisterPerformancePasses();
  if (!optimizer.Run(raw.data(), raw.size(), &spirv)) {
    if (ok) diags.error(passLoc, "spirv-opt failed");
    return false;
  }
  if (!tools.Validate(spirv)) {
    if (ok) diags.error(passLoc, "spirv-val rejected the optimised module");
    return false;
  }
  return ok;
}

}  // namespace

bool compileVulkan(const std::vector<SourceLine>& shader, const SourceLoc& passLoc, std::vector<uint32_t>& spirv,
                   Diagnostics& diags) {
  Compiled c;
  return parseAndLink(shader, passLoc, FrontEnd::Vulkan, c, diags) &&
         toSpirv(c, passLoc, SPV_ENV_VULKAN_1_1, spirv, diags);
}

bool compileOpenGlSpirv(const std::vector<SourceLine>& shader, const SourceLoc& passLoc, std::vector<uint32_t>& spirv,
                        Diagnostics& diags) {
  Compiled c;
  return parseAndLink(shader, passLoc, FrontEnd::OpenGlSpirv, c, diags) &&
         toSpirv(c, passLoc, SPV_ENV_OPENGL_4_5, spirv, diags);
}

bool checkEssl(const std::string& essl, const SourceLoc& passLoc, Diagnostics& diags) {
  Compiled c;
  return parseAndLink(textLines(essl, passLoc), passLoc, FrontEnd::Es310, c, diags);
}

bool compileHlsl(const std::string& hlsl, const SourceLoc& passLoc, const std::function<int(char, int)>& bindingOf,
                 bool optimise, std::vector<uint32_t>& spirv, Diagnostics& diags) {
  Compiled c;
  if (!parseAndLink(textLines(hlsl, passLoc), passLoc, FrontEnd::HlslVulkan, c, diags)) return false;
  bool ok = true;
  // OpDecorate <id> Binding <n>: n back from the shifted register to the Vulkan binding.
  auto rebind = [&](std::vector<uint32_t>& words) {
    for (std::size_t i = 5; i < words.size();) {
      const uint32_t count = words[i] >> 16, op = words[i] & 0xffffu;
      if (count == 0) break;
      if (op == 71 /* OpDecorate */ && count == 4 && words[i + 2] == 33 /* Binding */) {
        const uint32_t n = words[i + 3];
        const char cls = n >= kCbufferShift ? 'b' : n >= kSamplerShift ? 's' : n >= kTextureShift ? 't' : n >= kUavShift ? 'u' : '?';
        const unsigned shift = cls == 'b' ? kCbufferShift : cls == 's' ? kSamplerShift : cls == 't' ? kTextureShift : kUavShift;
        const int binding = cls == '?' ? -1 : bindingOf(cls, int(n - shift));
        if (binding < 0) {
          diags.error(passLoc, "HLSL round trip: binding " + std::to_string(n) + " is no register the pass description lists");
          ok = false;
        } else {
          words[i + 3] = uint32_t(binding);
        }
      }
      i += count;
    }
  };
  return toSpirv(c, passLoc, SPV_ENV_VULKAN_1_1, spirv, diags, rebind, optimise) && ok;
}

}  // namespace sao::codegen
