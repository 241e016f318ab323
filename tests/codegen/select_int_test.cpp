// sao-shaderc: a variant selected by an int setting whose values= are exactly [0,1] (the effect's
// ESTIMATOR by `estimator`) is accepted and names its setting; any other int setting is refused
// (the malformed corpus: select_int_setting, select_int_setting_values).
#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

#include "test_process.h"

namespace fs = std::filesystem;

TEST(ShadercSelect, IntSettingWithValuesZeroOneSelectsAVariant) {
  const fs::path out = fs::temp_directory_path() / ("sao_select_int_" + std::to_string(::getpid()));
  fs::remove_all(out);
  const auto r = sao::test::runCommand(std::string("'") + SAO_SHADERC + "' select_int.glsl -o '" + out.string() + "'",
                                       std::string(SAO_CODEGEN_TESTS_DIR) + "/select_int");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::string header = sao::test::readFile((out / "selint_effect.h").string());
  // Setting 0 (mode) selects MODE.
  EXPECT_NE(header.find("{\"MODE\", kVariantValues_MODE, 0, VariantSelect::Setting, 0,"), std::string::npos) << header;
  fs::remove_all(out);
}
