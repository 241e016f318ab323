// Depth EXRs as other tools write them; see foreign_exr.h.
#include "foreign_exr.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <half.h>

#include <memory>

namespace sao::test {
namespace {

// One part's pixels: every channel of `names` as `type`, `value(c, i)` for pixel i of channel c.
struct PartPixels {
  std::vector<std::vector<float>> f;
  std::vector<std::vector<half>> h;
};

Imf::FrameBuffer frameBuffer(const Imath::Box2i& dw, const std::vector<std::string>& names, Imf::PixelType type,
                             const std::function<float(std::size_t, std::size_t)>& value, PartPixels& px) {
  const std::size_t n = std::size_t(dw.max.x - dw.min.x + 1) * std::size_t(dw.max.y - dw.min.y + 1);
  px.f.assign(names.size(), std::vector<float>(n));
  px.h.assign(names.size(), std::vector<half>(n));
  Imf::FrameBuffer fb;
  for (std::size_t c = 0; c < names.size(); ++c) {
    for (std::size_t i = 0; i < n; ++i) {
      px.f[c][i] = value(c, i);
      px.h[c][i] = half(px.f[c][i]);
    }
    const void* ptr = type == Imf::HALF ? static_cast<const void*>(px.h[c].data()) : px.f[c].data();
    fb.insert(names[c], Imf::Slice::Make(type, ptr, dw));
  }
  return fb;
}

}  // namespace

void writeForeignDepth(const std::string& path, const ForeignDepth& f) {
  const Imath::Box2i dw(f.origin, f.origin + Imath::V2i(f.width - 1, f.height - 1));
  const Imath::Box2i display = f.display.value_or(dw);
  std::vector<Imf::Header> headers;
  for (std::size_t p = 0; p < f.partsBefore.size(); ++p) {
    Imf::Header h(display, dw);
    h.compression() = f.compression;
    for (const std::string& c : f.partsBefore[p]) h.channels().insert(c, Imf::Channel(Imf::HALF));
    h.setName("beauty" + std::to_string(p));
    h.setType(Imf::SCANLINEIMAGE);
    headers.push_back(h);
  }
  Imf::Header depthHeader(display, dw);
  depthHeader.compression() = f.compression;
  for (const std::string& c : f.channels) depthHeader.channels().insert(c, Imf::Channel(f.type));
  if (!f.partsBefore.empty()) {
    depthHeader.setName("depth");
    depthHeader.setType(Imf::SCANLINEIMAGE);
  }
  if (f.decorate) f.decorate(depthHeader);
  headers.push_back(depthHeader);

  // A single part is written as a plain file (OutputFile), as most tools do.
  std::unique_ptr<Imf::MultiPartOutputFile> multi;
  std::unique_ptr<Imf::OutputFile> single;
  if (headers.size() > 1) multi = std::make_unique<Imf::MultiPartOutputFile>(path.c_str(), headers.data(), int(headers.size()));
  else single = std::make_unique<Imf::OutputFile>(path.c_str(), headers[0]);
  for (std::size_t p = 0; p < headers.size(); ++p) {
    const bool isDepth = p + 1 == headers.size();
    std::vector<std::string> names;
    for (auto it = headers[p].channels().begin(); it != headers[p].channels().end(); ++it) names.push_back(it.name());
    PartPixels px;
    const Imf::PixelType type = isDepth ? f.type : Imf::HALF;
    const Imf::FrameBuffer fb = frameBuffer(dw, names, type,
                                            [&](std::size_t c, std::size_t i) {
                                              if (!isDepth) return 0.25f;
                                              return names[c] == f.depthChannel ? f.depth[i] : 0.5f;
                                            },
                                            px);
    if (single) {
      single->setFrameBuffer(fb);
      single->writePixels(f.height);
    } else {
      Imf::OutputPart part(*multi, int(p));
      part.setFrameBuffer(fb);
      part.writePixels(f.height);
    }
  }
}

}  // namespace sao::test
