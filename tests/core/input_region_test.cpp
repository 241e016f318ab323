// checkSupplied with inputs that are regions of larger textures (the backends' Inputs::region):
// every input must hold the input extent from the shared offset on; nothing is clamped.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <numbers>
#include <string>

#include "sao/schedule.h"

namespace {

using sao::gen::ResourceId;

sao::Camera camera(std::uint32_t w, std::uint32_t h, std::uint32_t guard) {
  sao::Camera c = sao::perspectiveCamera(std::numbers::pi / 3, w, h, 0.1, 100.0, sao::ClipDepth::ZeroToOne, false);
  c.guardBand = guard;
  return c;
}

std::size_t at(ResourceId id) { return static_cast<std::size_t>(id); }

TEST(InputRegion, InputsMayBeLargerThanTheRegionAtTheirOffset) {
  sao::Plan p;  // 641x359, guard 3: the region is 647x365
  ASSERT_TRUE(sao::plan(sao::Settings{}, camera(641, 359, 3), {sao::DepthEncoding::Hardware, {.depth2 = true, .normals = true}}, p).ok());
  ASSERT_EQ(p.inputExtent, (sao::Extent{647, 365}));
  sao::SuppliedImages in{};
  for (ResourceId id : {ResourceId::depth, ResourceId::depth2, ResourceId::normals}) in[at(id)] = {true, {700, 400}, sao::Offset{3, 5}};
  EXPECT_TRUE(sao::checkSupplied(p, in, false, "test").ok());
  for (ResourceId id : {ResourceId::depth, ResourceId::depth2, ResourceId::normals}) in[at(id)].region = sao::Offset{53, 35};
  EXPECT_TRUE(sao::checkSupplied(p, in, false, "test").ok()) << "the region at the far corner";
  // The 1279x720 camera over a 1280x720 depth buffer (dynamic resolution at the origin).
  sao::Plan wide;
  ASSERT_TRUE(sao::plan(sao::Settings{}, camera(1279, 720, 0), {}, wide).ok());
  sao::SuppliedImages one{};
  one[at(ResourceId::depth)] = {true, {1280, 720}, {}};
  EXPECT_FALSE(sao::checkSupplied(wide, one, false, "test").ok()) << "a larger texture needs a declared region";
  one[at(ResourceId::depth)].region = sao::Offset{};
  EXPECT_TRUE(sao::checkSupplied(wide, one, false, "test").ok());
  one[at(ResourceId::depth)].region = sao::Offset{1, 0};
  EXPECT_TRUE(sao::checkSupplied(wide, one, false, "test").ok());
}

TEST(InputRegion, ARegionOutsideAnyInputIsRefusedNamingOffsetExtentAndSize) {
  sao::Plan p;
  ASSERT_TRUE(sao::plan(sao::Settings{}, camera(641, 359, 3), {sao::DepthEncoding::Hardware, {.depth2 = true, .normals = true}}, p).ok());
  const sao::SuppliedImage good{true, {700, 400}, sao::Offset{53, 35}};
  struct Case {
    ResourceId input;
    sao::SuppliedImage image;
    const char* needle;
  };
  constexpr std::uint32_t kMax = std::numeric_limits<std::uint32_t>::max();
  const Case cases[] = {
      {ResourceId::depth, {true, {700, 400}, sao::Offset{54, 35}},
       "the depth input is 700x400, the camera needs 647x365 (the viewport 641x359 plus twice the guard band 3) at "
       "offset (54, 35), which ends at (701, 400): the region must lie inside the texture"},
      {ResourceId::depth, {true, {700, 400}, sao::Offset{53, 36}}, "ends at (700, 401)"},
      {ResourceId::depth2, {true, {699, 400}, sao::Offset{53, 35}}, "the depth2 input is 699x400"},
      {ResourceId::normals, {true, {647, 365}, sao::Offset{53, 35}}, "the normals input is 647x365"},
      {ResourceId::depth, {true, {700, 400}, sao::Offset{kMax, 0}}, "offset (4294967295, 0), which ends at (4294967942, 365)"},
      {ResourceId::depth, {true, {700, 400}, sao::Offset{0, kMax - 100}}, "which ends at (647, 4294967560)"},
      {ResourceId::depth, {true, {646, 365}, {}}, "the depth input is 646x365, the camera needs 647x365"},
      {ResourceId::depth, {true, {700, 400}, {}},
       "the depth input is 700x400, the camera needs 647x365 (the viewport 641x359 plus twice the guard band 3); to "
       "read a region of a larger texture, set Inputs::region"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.needle);
    sao::SuppliedImages in{};
    for (ResourceId id : {ResourceId::depth, ResourceId::depth2, ResourceId::normals}) in[at(id)] = good;
    in[at(c.input)] = c.image;
    const sao::Status st = sao::checkSupplied(p, in, false, "test");
    EXPECT_EQ(st.code, sao::StatusCode::InvalidInput);
    EXPECT_NE(st.message.find(c.needle), std::string::npos) << st.message;
  }
}

}  // namespace
