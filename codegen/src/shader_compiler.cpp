#include "shader_compiler.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <spirv-tools/libspirv.hpp>
#include <spirv-tools/optimizer.hpp>

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

bool parseAndLink(const std::vector<SourceLine>& lines, const SourceLoc& passLoc, bool vulkan, Compiled& c,
                  Diagnostics& diags) {
  const std::string text = joinLines(lines);
  const char* str = text.c_str();
  c.shader = std::make_unique<glslang::TShader>(EShLangCompute);
  c.shader->setStrings(&str, 1);
  EShMessages messages = EShMsgDefault;
  if (vulkan) {
    c.shader->setEnvInput(glslang::EShSourceGlsl, EShLangCompute, glslang::EShClientVulkan, 100);
    c.shader->setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_1);
    c.shader->setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_3);
    messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
  } else {
    c.shader->setEnvInput(glslang::EShSourceGlsl, EShLangCompute, glslang::EShClientNone, 0);
  }
  if (!c.shader->parse(GetDefaultResources(), vulkan ? 450 : 430, false, messages)) {
    reportLog(c.shader->getInfoLog(), lines, passLoc, diags);
    return false;
  }
  reportLog(c.shader->getInfoLog(), lines, passLoc, diags);  // warnings
  c.program = std::make_unique<glslang::TProgram>();
  c.program->addShader(c.shader.get());
  if (!c.program->link(messages)) {
    reportLog(c.program->getInfoLog(), lines, passLoc, diags);
    return false;
  }
  return true;
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
  if (!parseAndLink(shader, passLoc, false, c, diags)) return false;
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

bool compileVulkan(const std::vector<SourceLine>& shader, const SourceLoc& passLoc, std::vector<uint32_t>& spirv,
                   Diagnostics& diags) {
  Compiled c;
  if (!parseAndLink(shader, passLoc, true, c, diags)) return false;
  std::vector<uint32_t> raw;
  glslang::SpvOptions options;
  options.disableOptimizer = true;  // spirv-opt below, with validation before and after
  options.validate = false;
  spv::SpvBuildLogger logger;
  glslang::GlslangToSpv(*c.program->getIntermediate(EShLangCompute), raw, &logger, &options);
  if (!logger.getAllMessages().empty()) diags.warning(passLoc, "glslang SPIR-V: " + logger.getAllMessages());

  bool ok = true;
  auto consumer = [&](spv_message_level_t level, const char*, const spv_position_t& pos, const char* message) {
    if (level <= SPV_MSG_ERROR) {
      diags.error(passLoc, "spirv-val: " + spvMessage(message, pos));
      ok = false;
    }
  };
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_1);
  tools.SetMessageConsumer(consumer);
  if (!tools.Validate(raw)) return false;

  spvtools::Optimizer optimizer(SPV_ENV_VULKAN_1_1);
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

}  // namespace sao::codegen
