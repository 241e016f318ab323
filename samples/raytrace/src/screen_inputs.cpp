#include "screen_inputs.h"

namespace sao::raytrace::detail {
namespace {

bool sameExtent(Extent a, Extent b) { return a.width == b.width && a.height == b.height; }

}  // namespace

Status checkScreenInputs(const std::string& who, const Settings& settings, const Camera& camera,
                         const ConvergedInputs& in, gen::ParamBlock& block) {
  auto invalid = [&who](const std::string& what) { return Status::error(StatusCode::InvalidInput, who + ": " + what); };
  if (in.depth == nullptr) return invalid("needs a depth image");
  const DepthEncoding encoding = in.depth->format == DepthFormat::LinearZ ? DepthEncoding::LinearZ : DepthEncoding::Hardware;
  if (Status st = computeConstants(settings, camera, encoding, block); !st) return st;
  const std::uint32_t g = camera.guardBand;
  const Extent input{camera.width + 2 * g, camera.height + 2 * g};
  auto size = [](Extent e) { return std::to_string(e.width) + "x" + std::to_string(e.height); };
  if (!sameExtent(in.depth->extent, input) || in.depth->texels.size() != std::size_t(input.width) * input.height)
    return invalid("the depth is " + size(in.depth->extent) + ", the camera needs " + size(input) + " (viewport + guard band)");
  if (in.depth2 && (!sameExtent(in.depth2->extent, input) || in.depth2->format != in.depth->format ||
                    in.depth2->texels.size() != in.depth->texels.size()))
    return invalid("the second depth layer must have the depth's extent and format");
  if (in.normals && (!sameExtent(in.normals->extent, input) || in.normals->channels < 3 ||
                     in.normals->data.size() != std::size_t(input.width) * input.height * in.normals->channels))
    return invalid("the normals must have the depth's extent and at least 3 channels");
  return Status::success();
}

cpu::detail::Image<double> linearZ(const DepthImage& depth, const cpu::detail::Block<double>& P) {
  cpu::detail::Image<double> z(int(depth.extent.width), int(depth.extent.height), 1);
  for (int y = 0; y < z.h; ++y)
    for (int x = 0; x < z.w; ++x) z.at(x, y) = cpu::detail::zFromDepth(depth.value(std::uint32_t(x), std::uint32_t(y)), P);
  return z;
}

}  // namespace sao::raytrace::detail
