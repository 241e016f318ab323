// sao::core on extreme input (docs/ROBUSTNESS.md): the library version, cameras whose sizes do not
// fit 32 bits once the guard band is added (computeConstants used to wrap the size around to 0 and
// convert log2(0) = -inf to int), and very long or odd setting text.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "sao/constants.h"
#include "sao/plan.h"
#include "sao/settings.h"
#include "sao/version.h"

namespace sao {
namespace {

TEST(CoreRobustness, LibraryVersionIsTheHeaders) {
  EXPECT_EQ(libraryVersion(), SAO_VERSION);
  EXPECT_EQ(SAO_VERSION, (SAO_VERSION_MAJOR << 16) | (SAO_VERSION_MINOR << 8) | SAO_VERSION_PATCH);
}

TEST(CoreRobustness, SizesBeyondThirtyTwoBits) {
  const struct {
    std::uint32_t w, h, guard;
  } cases[] = {{0x80000000u, 16, 0x40000000u},  // max(w, h) + 2 guard = 2^32: wrapped to 0 before
               {0xFFFFFFFFu, 0xFFFFFFFFu, 0xFFFFFFFFu},
               {16, 16, 0x7FFFFFFFu}};
  for (const auto& c : cases) {
    SCOPED_TRACE(std::to_string(c.w) + "x" + std::to_string(c.h) + " guard " + std::to_string(c.guard));
    Camera camera = perspectiveCamera(std::numbers::pi / 3, 64, 36, 0.1, 100.0, ClipDepth::ZeroToOne, false);
    camera.width = c.w;
    camera.height = c.h;
    camera.guardBand = c.guard;
    Plan plan;
    const Status planned = sao::plan(Settings{}, camera, {}, plan);
    EXPECT_EQ(planned.code, StatusCode::InvalidExtent) << planned.message;
    EXPECT_NE(planned.message.find("exceeds the largest supported side"), std::string::npos) << planned.message;
    // The constants alone (no images) are still computed, finite and within the MIP limit.
    ParamBlock p{};
    const Status st = computeConstants(Settings{}, camera, DepthEncoding::Hardware, p);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_GE(p.max_mip, 0);
    EXPECT_LT(p.max_mip, gen::SAO_MAX_MIP_LEVELS);
    for (float v : {p.proj_info.x, p.proj_info.y, p.proj_info.z, p.proj_info.w, p.proj_scale, p.radius})
      EXPECT_TRUE(std::isfinite(v));
  }
}

TEST(CoreRobustness, LongAndOddSettingText) {
  Settings s;
  const Settings before = s;
  for (const std::string& text :
       {std::string(1 << 20, '9'), "radius=" + std::string(1 << 20, '1'), "radius=" + std::string(100000, ' '),
        std::string("radius=1\0x", 10), std::string("radius=1e-400"), std::string("radius=0x1p+9"),
        std::string("samples=") + std::string(400, '9'), std::string("use_z_hierarchy=TRUE"),
        std::string("=="), std::string("radius==1"), std::string("\xff\xfe=\x80")}) {
    const Status st = setFromAssignment(s, text);
    EXPECT_FALSE(st.ok()) << text.substr(0, 40);
    EXPECT_EQ(st.code, StatusCode::InvalidSetting);
    EXPECT_FALSE(st.message.empty());
  }
  EXPECT_EQ(gen::settingValue(s, SettingId::radius), gen::settingValue(before, SettingId::radius));
  EXPECT_TRUE(validate(s).ok());
  // strtod's other spellings of a number are numbers: hexadecimal floats, leading '+', exponents.
  EXPECT_TRUE(setFromAssignment(s, "radius=0x1p-3").ok());
  EXPECT_EQ(s.radius, 0.125f);
  EXPECT_TRUE(setFromAssignment(s, "radius=+2e0").ok());
}

}  // namespace
}  // namespace sao
