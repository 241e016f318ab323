// make_foreign_depth MODE IN.exr OUT.exr: rewrites a depth file sao-render wrote (--save-depth:
// D32F, reversed-Z, with its sao.* camera) as another tool would write the same depth, for
// depth_foreign_files.sh. Modes:
//   dwaa, dwab        the same file, DWAA / DWAB compressed
//   parts             two parts: a beauty (R, G, B, A) first, the depth ("Z", camera) second
//   blender           Blender's multilayer names: ViewLayer.Combined.R/G/B/A, ViewLayer.Depth.Z,
//                     ViewLayer.Normal.X/Y/Z (one part, with the camera)
//   m44f              sao.projection as m44f (what OpenImageIO and Python write)
//   noversion         every sao.* attribute but sao.version
//   crop              the data window cropped to the middle half of each side, the display window
//                     the whole view (with the camera)
//   distances         no camera: positive distances along the view axis, sky 1e10 (a Blender Z pass)
//   linear-z          no camera: camera-space z (negative in front), sky +0
//   standard-half     no camera: standard (not reversed) [0,1] depth with a far plane at 100, HALF
//   standard-float    the same as FLOAT
//   reversed-half     no camera: the input's reversed-Z depth as HALF
//   reversed-b44      no camera: the input's reversed-Z depth as HALF, B44 compressed
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfMatrixAttribute.h>
#include <half.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <string>

#include "../io/foreign_exr.h"
#include "sao/io.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: make_foreign_depth MODE IN.exr OUT.exr\n");
    return 2;
  }
  const std::string mode = argv[1], in = argv[2], out = argv[3];
  sao::DepthImage depth;
  sao::Camera camera;
  bool hasCamera = false;
  if (sao::Status s = sao::readDepthExr(in, depth, camera, hasCamera); !s || !hasCamera ||
                                                                      depth.format != sao::DepthFormat::D32F) {
    std::fprintf(stderr, "make_foreign_depth: %s is not a D32F depth file with a camera: %s\n", in.c_str(),
                 s.message.c_str());
    return 2;
  }
  sao::DepthModel model;
  if (!sao::analyze(camera, model)) return 2;
  const int w = int(depth.extent.width), h = int(depth.extent.height);
  const Imf::Header source = Imf::InputFile(in.c_str()).header();

  sao::test::ForeignDepth f;
  f.width = w;
  f.height = h;
  // The file's top row first: image row h - 1 - y.
  auto stored = [&](int x, int y) { return std::bit_cast<float>(depth.texels[std::size_t(h - 1 - y) * w + x]); };
  auto each = [&](auto value) {
    f.depth.clear();
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) f.depth.push_back(value(stored(x, y)));
  };
  each([](float d) { return d; });
  bool keepCamera = true, m44f = false, dropVersion = false;
  if (mode == "dwaa") {
    f.compression = Imf::DWAA_COMPRESSION;
  } else if (mode == "dwab") {
    f.compression = Imf::DWAB_COMPRESSION;
  } else if (mode == "parts") {
    f.partsBefore = {{"R", "G", "B", "A"}};
  } else if (mode == "blender") {
    f.channels = {"ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B", "ViewLayer.Combined.A",
                  "ViewLayer.Depth.Z",    "ViewLayer.Normal.X",   "ViewLayer.Normal.Y",   "ViewLayer.Normal.Z"};
    f.depthChannel = "ViewLayer.Depth.Z";
  } else if (mode == "m44f") {
    m44f = true;
  } else if (mode == "noversion") {
    dropVersion = true;
  } else if (mode == "crop") {
    f.display = Imath::Box2i({0, 0}, {w - 1, h - 1});
    f.origin = {w / 4, h / 4};
    f.width = w / 2;
    f.height = h / 2;
    f.depth.clear();
    for (int y = h / 4; y < h / 4 + h / 2; ++y)
      for (int x = w / 4; x < w / 4 + w / 2; ++x) f.depth.push_back(stored(x, y));
  } else if (mode == "distances") {
    keepCamera = false;
    each([&](float d) { return d == 0.0f ? 1e10f : float(-sao::linearZ(model, camera.kind, d)); });
  } else if (mode == "linear-z") {
    keepCamera = false;
    each([&](float d) { return d == 0.0f ? 0.0f : float(sao::linearZ(model, camera.kind, d)); });
  } else if (mode == "standard-half" || mode == "standard-float") {
    keepCamera = false;
    // Window depth of a [0, 1] standard projection with near n and far 100: d = f (z + n) / (z (f - n))
    // for camera-space z < 0 (z = -n gives 0, z = -f gives 1).
    const double n = model.nearDistance, far = 100.0;
    each([&](float d) {
      if (d == 0.0f) return 1.0f;
      const double z = sao::linearZ(model, camera.kind, d);
      return float(std::min(1.0, far * (z + n) / (z * (far - n))));
    });
    if (mode == "standard-half") f.type = Imf::HALF;
  } else if (mode == "reversed-half" || mode == "reversed-b44") {
    keepCamera = false;
    f.type = Imf::HALF;
    if (mode == "reversed-b44") f.compression = Imf::B44_COMPRESSION;
  } else {
    std::fprintf(stderr, "make_foreign_depth: unknown mode '%s'\n", mode.c_str());
    return 2;
  }
  if (keepCamera)
    f.decorate = [&](Imf::Header& header) {
      for (auto it = source.begin(); it != source.end(); ++it) {
        const std::string name = it.name();
        if (name.rfind("sao.", 0) != 0 || (dropVersion && name == "sao.version")) continue;
        if (m44f && name == "sao.projection") {
          const auto& m = static_cast<const Imf::M44dAttribute&>(it.attribute()).value();
          Imath::M44f single;
          for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) single[i][j] = float(m[i][j]);
          header.insert(name, Imf::M44fAttribute(single));
        } else {
          header.insert(name, it.attribute());
        }
      }
    };
  try {
    sao::test::writeForeignDepth(out, f);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_foreign_depth: %s\n", e.what());
    return 1;
  }
  return 0;
}
