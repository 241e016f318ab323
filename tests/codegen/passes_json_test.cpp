// sao_passes.json, the pass description an engine's own renderer reads beside the shader files,
// says what the generated tables say: every pass, its local size and levels, every compiled variant
// with its files, bindings, shared memory and push constants, and the two blocks' sizes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "sao_effect.h"

namespace gen = sao::gen;
namespace fs = std::filesystem;

namespace {

nlohmann::json readManifest() {
  std::ifstream in(SAO_PASSES_JSON);
  return nlohmann::json::parse(in);  // throws (a failed test) on a missing or malformed file
}

TEST(PassesJson, AgreesWithTheGeneratedTables) {
  const nlohmann::json j = readManifest();
  EXPECT_EQ(j["effect"], std::string(gen::kEffectName));
  EXPECT_EQ(j["version"], gen::kEffectVersion);
  EXPECT_EQ(j["parameter_block"]["bytes"], sizeof(gen::ParamBlock));
  EXPECT_EQ(j["push_constants"]["bytes"], gen::kPushConstantBytes);
  EXPECT_EQ(j["push_constants"]["members"].size() * 4, gen::kPushConstantBytes);
  ASSERT_EQ(j["passes"].size(), gen::passes().size());
  const fs::path folder = fs::path(SAO_PASSES_JSON).parent_path();
  std::size_t variants = 0;
  for (std::size_t p = 0; p < gen::passes().size(); ++p) {
    const gen::PassInfo& pass = gen::passes()[p];
    const nlohmann::json& jp = j["passes"][p];
    SCOPED_TRACE(std::string(pass.name));
    EXPECT_EQ(jp["name"], std::string(pass.name));
    EXPECT_EQ(jp["local_size"][0], pass.localX);
    EXPECT_EQ(jp["local_size"][1], pass.localY);
    EXPECT_EQ(jp["levels"].is_null(), pass.levelSlots == 0);
    ASSERT_EQ(jp["compiled"].size(), pass.compiled.size());
    for (std::size_t v = 0; v < pass.compiled.size(); ++v, ++variants) {
      const gen::PassVariantInfo& info = pass.compiled[v];
      const nlohmann::json& jv = jp["compiled"][v];
      EXPECT_EQ(jv["spirv"], std::string(info.fileStem) + ".spv");
      EXPECT_TRUE(fs::exists(folder / jv["spirv"].get<std::string>()));
      EXPECT_TRUE(fs::exists(folder / jv["glsl"].get<std::string>()));
      EXPECT_EQ(jv["shared_bytes"], info.sharedBytes);
      EXPECT_EQ(jv["push_constant_bytes"], info.pushConstantBytes);
      for (std::size_t k = 0; k < gen::kVariantCount; ++k) {
        const std::string name(gen::kVariants[k].name);
        if (info.values[k] < 0) EXPECT_FALSE(jv["variant_values"].contains(name));
        else EXPECT_EQ(jv["variant_values"][name], info.values[k]);
      }
      ASSERT_EQ(jv["bindings"].size(), info.bindings.size());
      for (std::size_t b = 0; b < info.bindings.size(); ++b) {
        const gen::BindingInfo& bi = info.bindings[b];
        const nlohmann::json& jb = jv["bindings"][b];
        EXPECT_EQ(jb["vulkan_binding"], bi.binding);
        EXPECT_EQ(jb["gl_unit"], bi.glUnit);
        EXPECT_EQ(jb["resource"], std::string(gen::kResources[static_cast<std::size_t>(bi.resource)].name));
        EXPECT_EQ(jb["access"] != "read", bi.write);
        EXPECT_EQ(jb["access"] == "read_write", bi.readWrite);
        EXPECT_EQ(jb["slots"], bi.slots);
      }
    }
  }
  EXPECT_GT(variants, 0u);
}

}  // namespace
