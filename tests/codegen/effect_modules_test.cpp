// Every module the real SAO effect embeds is validated again here: SPIR-V by spirv-val's library
// for Vulkan 1.1, GLSL by glslang as OpenGL compiles it; the pass table is consistent.
#include <gtest/gtest.h>

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <spirv-tools/libspirv.hpp>

#include <set>

#include "sao_effect.h"

namespace gen = sao::gen;

TEST(EffectModules, EverySpirvModuleValidatesForVulkan11) {
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_1);
  std::string messages;
  tools.SetMessageConsumer([&](spv_message_level_t, const char*, const spv_position_t&, const char* m) {
    messages += std::string(m) + "\n";
  });
  ASSERT_GT(gen::kSpirvBlobCount, 0u);
  for (std::uint32_t i = 0; i < gen::kSpirvBlobCount; ++i) {
    const auto spv = gen::spirvModule(i);
    EXPECT_TRUE(tools.Validate(spv.data(), spv.size())) << "blob " << i << ": " << messages;
  }
}

TEST(EffectModules, EveryGlslSourceCompilesAsOpenGl430) {
  glslang::InitializeProcess();
  for (std::uint32_t i = 0; i < gen::kGlslBlobCount; ++i) {
    const std::string text(gen::glslSource(i));
    ASSERT_EQ(text.rfind("#version 430\n", 0), 0u);
    const char* str = text.c_str();
    glslang::TShader shader(EShLangCompute);
    shader.setStrings(&str, 1);
    shader.setEnvInput(glslang::EShSourceGlsl, EShLangCompute, glslang::EShClientNone, 0);
    EXPECT_TRUE(shader.parse(GetDefaultResources(), 430, false, EShMsgDefault)) << shader.getInfoLog();
  }
  glslang::FinalizeProcess();
}

TEST(EffectModules, PassTableIsConsistent) {
  ASSERT_GE(gen::passes().size(), 5u);
  gen::VariantValues defaults{};
  for (std::size_t v = 0; v < gen::kVariantCount; ++v) defaults[v] = gen::kVariants[v].defaultValue;
  for (const auto& p : gen::passes()) {
    EXPECT_FALSE(p.compiled.empty()) << p.name;
    EXPECT_NE(gen::findPassVariant(static_cast<gen::PassId>(&p - gen::passes().data()), defaults), nullptr)
        << p.name << " has no variant for the default key";
    for (const auto& c : p.compiled) {
      std::set<std::uint32_t> seen;
      std::uint32_t expected = 1;  // 0 is the parameter block
      std::uint32_t textureUnit = 0, imageUnit = 0;  // GL: each counted from 0, an array's elements in a row
      for (const auto& b : c.bindings) {
        EXPECT_EQ(b.binding, expected) << p.name << " " << c.fileStem;
        EXPECT_TRUE(seen.insert(b.binding).second);
        EXPECT_EQ(b.slots, b.write && p.levelSlots ? p.levelSlots : 1u) << p.name << " " << c.fileStem;
        EXPECT_EQ(b.glUnit, b.write ? imageUnit : textureUnit) << p.name << " " << c.fileStem;
        expected += b.slots;
        (b.write ? imageUnit : textureUnit) += b.slots;
        const auto& r = gen::kResources[static_cast<std::size_t>(b.resource)];
        if (r.whenVariant >= 0) {
          EXPECT_NE(c.values[r.whenVariant], 0) << r.name << " bound while absent";
        }
      }
      // GL's minimum GL_MAX_COMPUTE_IMAGE_UNIFORMS and GL_MAX_IMAGE_UNITS: every pass runs on any GL 4.3.
      EXPECT_LE(imageUnit, 8u) << p.name << " " << c.fileStem;
    }
  }
}
