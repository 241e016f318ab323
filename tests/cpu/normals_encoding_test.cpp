// The normals encodings (Camera::normalsEncoding, Camera::viewRotation) on the CPU reference: a
// scene's camera-space normals re-encoded in world space and/or octahedral give the camera-space
// run's AO within the backends' agreement bounds (p99.9 <= 2/255, max <= 4/255), and the encoding
// contract is enforced: a world-space encoding needs a view rotation, and a view rotation must be
// one.
#include <cstdio>
#include <limits>
#include <string>

#include "normal_encodings.h"
#include "sao/constants.h"
#include "sao/presets.h"
#include "test_support.h"

namespace sao::test {
namespace {

using cpu::Precision;

constexpr double kWithin = 2.0 / 255.0, kNever = 4.0 / 255.0;

const char* name(NormalsEncoding e) {
  switch (e) {
    case NormalsEncoding::CameraXyz: return "camera_xyz";
    case NormalsEncoding::WorldXyz: return "world_xyz";
    case NormalsEncoding::CameraOctahedral: return "camera_octahedral";
    case NormalsEncoding::WorldOctahedral: return "world_octahedral";
  }
  return "?";
}

Camera rotatedCamera(NormalsEncoding e) {
  Camera c = testCamera();
  c.normalsEncoding = e;
  c.viewRotation = viewRotation(0.7, -0.4, 0.25);
  return c;
}

TEST(NormalsEncoding, EveryEncodingGivesTheCameraSpaceResult) {
  for (const Scene& scene : {sphereOnPlaneScene(), stairsScene(), creaseScene(2.0)}) {
    const Camera base = testCamera();
    const DepthImage depth = renderDepth(scene, base, DepthFormat::D32F);
    const FloatImage n = renderNormals(scene, base);
    for (Precision p : {Precision::Float, Precision::Double}) {
      cpu::Inputs in;
      in.depth = &depth;
      in.normals = &n;
      const cpu::Result ref = runOrFail(presetSettings(Preset::Medium), base, in, p);
      for (NormalsEncoding e : {NormalsEncoding::WorldXyz, NormalsEncoding::CameraOctahedral,
                                NormalsEncoding::WorldOctahedral}) {
        SCOPED_TRACE(scene.name + " " + name(e) + " " + cpu::toString(p));
        const Camera cam = rotatedCamera(e);
        const FloatImage encoded = encodeNormals(n, e, *cam.viewRotation);
        cpu::Inputs ein = in;
        ein.normals = &encoded;
        const cpu::Result r = runOrFail(presetSettings(Preset::Medium), cam, ein, p);
        EXPECT_EQ(r.params.normals_encoding, int(e));
        const std::string label = std::string("cpu_normals_") + name(e) + "_" + scene.name + "_" + cpu::toString(p);
        const Agreement f = compare(r.ao, ref.ao, 0, kWithin, kNever, "failures", label + "_final");
        const Agreement w = compare(r.aoRaw, ref.aoRaw, 0, kWithin, kNever, "failures", label + "_raw");
        std::printf("NORMALS %-17s %-16s %-6s vs camera xyz: final max %.4f/255 p99.9 %.4f/255 | raw max %.4f/255 "
                    "p99.9 %.4f/255\n",
                    name(e), scene.name.c_str(), cpu::toString(p), f.maxAbs * 255, f.p999 * 255, w.maxAbs * 255,
                    w.p999 * 255);
        EXPECT_TRUE(acceptable(f)) << "final max " << f.maxAbs * 255 << "/255, p99.9 " << f.p999 * 255 << "/255";
        EXPECT_TRUE(acceptable(w)) << "raw max " << w.maxAbs * 255 << "/255, p99.9 " << w.p999 * 255 << "/255";
      }
    }
  }
}

// The camera-space encoding ignores a (valid) view rotation: the same bits with or without one.
TEST(NormalsEncoding, CameraSpaceIgnoresTheRotation) {
  const Camera base = testCamera();
  const DepthImage depth = renderDepth(stairsScene(), base, DepthFormat::D32F);
  const FloatImage n = renderNormals(stairsScene(), base);
  cpu::Inputs in;
  in.depth = &depth;
  in.normals = &n;
  const cpu::Result a = runOrFail(Settings{}, base, in, Precision::Float);
  const cpu::Result b = runOrFail(Settings{}, rotatedCamera(NormalsEncoding::CameraXyz), in, Precision::Float);
  EXPECT_TRUE(sameBits(a.ao, b.ao));
  EXPECT_TRUE(sameBits(a.aoRaw, b.aoRaw));
}

Status runWith(const Camera& cam) {
  const DepthImage depth = renderDepth(planeScene(2.0), testCamera(), DepthFormat::D32F);
  const FloatImage n = renderNormals(planeScene(2.0), testCamera());
  cpu::Inputs in;
  in.depth = &depth;
  in.normals = &n;
  cpu::Result r;
  return cpu::run(Settings{}, cam, in, cpu::Options{Precision::Float, 1}, r);
}

void expectRefused(const Camera& cam, const std::string& part) {
  const Status st = runWith(cam);
  EXPECT_EQ(st.code, StatusCode::InvalidCamera) << st.message;
  EXPECT_NE(st.message.find(part), std::string::npos) << st.message;
  ParamBlock p;
  EXPECT_EQ(computeConstants(Settings{}, cam, DepthEncoding::Hardware, p).message, st.message);
}

TEST(NormalsEncoding, WorldSpaceNeedsARotation) {
  for (NormalsEncoding e : {NormalsEncoding::WorldXyz, NormalsEncoding::WorldOctahedral}) {
    Camera c = testCamera();
    c.normalsEncoding = e;
    expectRefused(c, std::string("Camera::normalsEncoding = ") +
                         (e == NormalsEncoding::WorldXyz ? "WorldXyz" : "WorldOctahedral") +
                         " (world-space normals) needs Camera::viewRotation");
  }
  Camera c = testCamera();
  c.normalsEncoding = NormalsEncoding(7);
  expectRefused(c, "Camera::normalsEncoding = 7 is not a NormalsEncoding");
}

TEST(NormalsEncoding, ViewRotationMustBeARotation) {
  Camera c = rotatedCamera(NormalsEncoding::WorldXyz);
  EXPECT_TRUE(runWith(c).ok());
  const std::array<double, 9> good = *c.viewRotation;

  std::array<double, 9> scaled = good;
  for (std::size_t i = 0; i < 3; ++i) scaled[i] *= 1.1;  // column 0 longer
  c.viewRotation = scaled;
  expectRefused(c, "Camera::viewRotation is not a rotation: column 0 has length 1.1");

  std::array<double, 9> sheared = good;
  for (std::size_t i = 0; i < 3; ++i) sheared[3 + i] += 0.01 * good[i];  // column 1 leans on column 0
  c.viewRotation = sheared;
  expectRefused(c, "Camera::viewRotation is not a rotation: columns 0 and 1 have the dot product");

  std::array<double, 9> mirrored = good;
  for (std::size_t i = 0; i < 3; ++i) mirrored[6 + i] = -mirrored[6 + i];
  c.viewRotation = mirrored;
  expectRefused(c, "Camera::viewRotation is a reflection (determinant -1), not a rotation");

  std::array<double, 9> nan = good;
  nan[4] = std::numeric_limits<double>::quiet_NaN();
  c.viewRotation = nan;
  expectRefused(c, "Camera::viewRotation has a non-finite element");

  // A rotation that is set is checked with a camera-space encoding too.
  c.normalsEncoding = NormalsEncoding::CameraXyz;
  c.viewRotation = scaled;
  expectRefused(c, "column 0 has length");

  // Float-stored rotations (rounding ~1e-7) pass.
  std::array<double, 9> rounded = good;
  for (double& v : rounded) v = double(float(v));
  c.viewRotation = rounded;
  EXPECT_TRUE(runWith(c).ok());
}

}  // namespace
}  // namespace sao::test
