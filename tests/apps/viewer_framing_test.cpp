// sao-viewer's framing for the strip beside the panel (samples/viewer/framing.h): which strip,
// and that the whole-window picture lands in it, for both projection kinds, with a camera the
// effect accepts (an off-axis matrix: analyze() and computeConstants()).
#include <gtest/gtest.h>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "framing.h"
#include "sao/constants.h"

namespace sao::viewer {
namespace {

TEST(ViewerFraming, FreeStripIsTheWiderSideOfAShownPanel) {
  EXPECT_EQ(freeStrip(false, 0.00625, 0.28625), (Strip{0, 1}));  // hidden (H) or collapsed
  EXPECT_EQ(freeStrip(true, 0.00625, 0.28625), (Strip{0.28625, 1}));  // the default: left edge
  EXPECT_EQ(freeStrip(true, 0.7, 0.99), (Strip{0, 0.7}));           // moved to the right edge
  EXPECT_EQ(freeStrip(true, 0.3, 0.5), (Strip{0.5, 1}));            // the wider side
  EXPECT_EQ(freeStrip(true, 0.2, 0.8), (Strip{0, 1}));              // under a quarter either side
  EXPECT_EQ(freeStrip(true, -0.5, 0.1), (Strip{0.1, 1}));           // partly off the window
}

// ndc x, y of a camera-space point through the projection.
glm::dvec2 ndc(const Camera& c, glm::dvec3 p) {
  const glm::dvec4 clip = glm::make_mat4(c.projection.data()) * glm::dvec4(p, 1.0);
  return glm::dvec2(clip) / clip.w;
}

void expectFramedInStrip(Camera c, Strip strip) {
  const Camera whole = c;
  frameInStrip(c, strip);
  // Every point lands where the whole-window picture puts it, scaled into the strip.
  const double s = strip.x1 - strip.x0, cx = strip.x0 + strip.x1 - 1.0;
  for (const glm::dvec3 p : {glm::dvec3(0, 0, -5), glm::dvec3(1.5, -0.7, -3), glm::dvec3(-4, 2, -20)}) {
    const glm::dvec2 before = ndc(whole, p), after = ndc(c, p);
    EXPECT_NEAR(after.x, s * before.x + cx, 1e-12);
    EXPECT_NEAR(after.y, s * before.y, 1e-12);
  }
  // The window's edges of the old picture are the strip's edges (in x).
  const glm::dvec3 leftEdge = whole.kind == ProjectionKind::Perspective
                                  ? glm::dvec3(-5.0 / whole.projection[0], 0, -5)
                                  : glm::dvec3(-1.0 / whole.projection[0], 0, -5);
  EXPECT_NEAR(0.5 * (ndc(c, leftEdge).x + 1.0), strip.x0, 1e-12);
  // The effect takes the off-axis camera, with the same depth model.
  DepthModel before, after;
  ASSERT_TRUE(analyze(whole, before).ok());
  const Status s2 = analyze(c, after);
  ASSERT_TRUE(s2.ok()) << s2.message;
  EXPECT_EQ(after.c0, before.c0);
  EXPECT_EQ(after.c2, before.c2);
  ParamBlock block;
  const Status s3 = computeConstants(Settings{}, c, DepthEncoding::Hardware, block);
  EXPECT_TRUE(s3.ok()) << s3.message;
}

TEST(ViewerFraming, PerspectivePictureLandsInTheStrip) {
  expectFramedInStrip(perspectiveCamera(1.0, 1280, 720, 0.1, INFINITY, ClipDepth::ZeroToOne, true),
                      Strip{0.28625, 1});
  expectFramedInStrip(perspectiveCamera(0.8, 640, 400, 0.1, 100, ClipDepth::NegativeOneToOne, false),
                      Strip{0, 0.6});
}

TEST(ViewerFraming, OrthographicPictureLandsInTheStrip) {
  expectFramedInStrip(orthographicCamera(3.0, 1280, 720, 0.1, 50, ClipDepth::ZeroToOne, true), Strip{0.28625, 1});
}

TEST(ViewerFraming, TheWholeWindowLeavesTheCameraAlone) {
  const Camera c = perspectiveCamera(1.0, 1280, 720, 0.1, INFINITY, ClipDepth::ZeroToOne, true);
  Camera framed = c;
  frameInStrip(framed, Strip{});
  EXPECT_EQ(framed, c);
}

}  // namespace
}  // namespace sao::viewer
