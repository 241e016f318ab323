// sao_passes.json, the pass description an engine's own renderer reads beside the shader files,
// says what the generated tables say: every pass, its local size and levels, every compiled variant
// with its files, bindings, shared memory and push constants, and the two blocks' sizes; per target,
// the HLSL registers and the GLES storage formats (the effect's `target gles` rule).
#include <gtest/gtest.h>

#include <algorithm>
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

// Every variant has its HLSL for both shader models; its registers are each class's own, counted
// from 0 in binding order (an array takes one per slot), with a read's sampler at its texture's
// number. A variant has a GLSL ES 3.10 file exactly when each of its writes has a GLES format: the
// one ES stores, or the rule's substitute; a refused format has none.
TEST(PassesJson, TargetsFollowTheRegisterRuleAndTheGlesRule) {
  const nlohmann::json j = readManifest();
  const fs::path folder = fs::path(SAO_PASSES_JSON).parent_path();
  const nlohmann::json& gles = j["targets"]["gles"];
  EXPECT_EQ(j["targets"]["hlsl"]["parameter_block"], "b0");
  EXPECT_EQ(j["targets"]["hlsl"]["push_constants"], "b1");
  std::size_t onGles = 0, total = 0;
  for (std::size_t p = 0; p < gen::passes().size(); ++p) {
    const gen::PassInfo& pass = gen::passes()[p];
    for (std::size_t v = 0; v < pass.compiled.size(); ++v, ++total) {
      const gen::PassVariantInfo& info = pass.compiled[v];
      const nlohmann::json& jv = j["passes"][p]["compiled"][v];
      SCOPED_TRACE(std::string(info.fileStem));
      EXPECT_TRUE(fs::exists(folder / jv["hlsl_sm50"].get<std::string>()));
      EXPECT_TRUE(fs::exists(folder / jv["hlsl_sm60"].get<std::string>()));
      EXPECT_EQ(jv["essl"].is_null(), info.esslBlob < 0);
      if (!jv["essl"].is_null()) { EXPECT_TRUE(fs::exists(folder / jv["essl"].get<std::string>())); }
      onGles += info.esslBlob >= 0;
      int t = 0, u = 0;
      bool refused = false;
      for (std::size_t b = 0; b < info.bindings.size(); ++b) {
        const gen::BindingInfo& bi = info.bindings[b];
        const nlohmann::json& jb = jv["bindings"][b];
        if (!bi.write) {
          EXPECT_EQ(jb["hlsl"]["srv"], "t" + std::to_string(t));
          EXPECT_EQ(jb["hlsl"]["sampler"], "s" + std::to_string(t++));
          continue;
        }
        EXPECT_EQ(jb["hlsl"]["uav"], "u" + std::to_string(u));
        u += int(bi.slots);
        const std::string format(gen::formatInfo(bi.format).name);
        const bool substituted = gles["storage"].contains(format);
        const std::string esFormat = substituted ? gles["storage"][format].get<std::string>() : format;
        refused = refused || std::find(gles["refused"].begin(), gles["refused"].end(), format) != gles["refused"].end();
        if (info.esslBlob < 0) continue;
        EXPECT_EQ(jb["gles"]["format"], esFormat);
        EXPECT_EQ(gen::formatInfo(bi.esFormat).name, esFormat);
        // Only r32f is read back through its image on GLES; other loaded writes through a texture unit
        // after the pass's reads.
        EXPECT_EQ(bi.esKeptUnit >= 0, bi.readWrite && esFormat != "r32f");
        if (bi.esKeptUnit >= 0) { EXPECT_EQ(jb["gles"]["kept_texture_unit"], bi.esKeptUnit); }
        if (bi.esKeptUnit >= 0) { EXPECT_EQ(bi.esKeptUnit, t); }
      }
      EXPECT_EQ(info.esslBlob < 0, refused);
    }
  }
  EXPECT_GT(onGles, 0u);
  EXPECT_LT(onGles, total);  // sao.glsl refuses r8 outputs on GLES
}

}  // namespace
