#include "frame.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/glm.hpp>

namespace sao::prepass::detail {

const char* formatName(DepthFormat format) { return sao::toString(format); }

Status checkMesh(const scenes::Mesh& mesh, std::uint64_t& digest) {
  if (mesh.indices.empty()) return Status::error(StatusCode::InvalidInput, "prepass: the mesh has no triangles");
  if (mesh.indices.size() % 3 != 0)
    return Status::error(StatusCode::InvalidInput, "prepass: the mesh has " + std::to_string(mesh.indices.size()) +
                                                       " indices, not a multiple of 3");
  if (mesh.indices.size() > std::size_t(UINT32_MAX) / 3)
    return Status::error(StatusCode::InvalidInput, "prepass: the mesh has too many triangles");
  // FNV-1a over the bytes of the positions and the indices, with the sizes mixed in.
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
  };
  const std::size_t sizes[2] = {mesh.positions.size(), mesh.indices.size()};
  mix(sizes, sizeof sizes);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return Status::error(StatusCode::InvalidInput, "prepass: mesh vertex " + std::to_string(i) + " is not finite");
  }
  mix(mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
  for (std::uint32_t i : mesh.indices)
    if (i >= mesh.positions.size())
      return Status::error(StatusCode::InvalidInput, "prepass: mesh index " + std::to_string(i) + " is out of range (" +
                                                         std::to_string(mesh.positions.size()) + " vertices)");
  mix(mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t));
  digest = h;
  return Status::success();
}

std::vector<float> expandMesh(const scenes::Mesh& mesh) {
  std::vector<float> v;
  v.reserve(mesh.indices.size() * kVertexFloats);
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::vec3 p[3] = {mesh.positions[mesh.indices[t]], mesh.positions[mesh.indices[t + 1]],
                            mesh.positions[mesh.indices[t + 2]]};
    const glm::dvec3 n = glm::cross(glm::dvec3(p[1]) - glm::dvec3(p[0]), glm::dvec3(p[2]) - glm::dvec3(p[0]));
    const double len = glm::length(n);
    const glm::dvec3 unit = len > 0 && std::isfinite(len) ? n / len : glm::dvec3(0.0);
    for (const glm::vec3& q : p) {
      v.insert(v.end(), {q.x, q.y, q.z, float(unit.x), float(unit.y), float(unit.z)});
    }
  }
  return v;
}

Status prepareFrame(const scenes::Mesh& mesh, const scenes::View& view, const Camera& camera,
                    const PrepassOptions& options, Frame& out) {
  out = Frame{};
  if (mesh.indices.empty()) return Status::error(StatusCode::InvalidInput, "prepass: the mesh has no triangles");
  for (double e : {view.eye.x, view.eye.y, view.eye.z, view.target.x, view.target.y, view.target.z, view.up.x,
                   view.up.y, view.up.z})
    if (!std::isfinite(e)) return Status::error(StatusCode::InvalidCamera, "prepass: the view is not finite");
  return prepareFrame(scenes::viewMatrix(view), camera, options, out);
}

Status prepareFrame(const glm::dmat4& viewM, const Camera& camera, const PrepassOptions& options, Frame& out) {
  out = Frame{};
  if (options.format == DepthFormat::LinearZ)
    return Status::error(StatusCode::UnsupportedFormat,
                         "prepass: LinearZ is not a depth-buffer format; use D16, D24 or D32F");
  if (options.format != DepthFormat::D16 && options.format != DepthFormat::D24 && options.format != DepthFormat::D32F)
    return Status::error(StatusCode::UnsupportedFormat, "prepass: unknown depth format");
  if (options.secondLayer && !(std::isfinite(options.minSeparation) && options.minSeparation > 0))
    return Status::error(StatusCode::InvalidInput, "prepass: minSeparation must be a finite number > 0 metres, not " +
                                                       std::to_string(options.minSeparation));
  if (camera.width == 0 || camera.height == 0)
    return Status::error(StatusCode::InvalidExtent, "prepass: the viewport is " + std::to_string(camera.width) + "x" +
                                                        std::to_string(camera.height) + "; both sides must be > 0");
  if (Status s = analyze(camera, out.model); !s) return Status::error(s.code, "prepass: " + s.message);
  const std::uint64_t w = std::uint64_t(camera.width) + 2ull * camera.guardBand;
  const std::uint64_t h = std::uint64_t(camera.height) + 2ull * camera.guardBand;
  if (w > UINT32_MAX / 2 || h > UINT32_MAX / 2)
    return Status::error(StatusCode::InvalidExtent, "prepass: the image with its guard band is too large");
  out.extent = {std::uint32_t(w), std::uint32_t(h)};
  if (!(std::isfinite(camera.metersToViewUnits) && camera.metersToViewUnits > 0))
    return Status::error(StatusCode::InvalidCamera, "prepass: metersToViewUnits must be finite and > 0");
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(viewM[c][r]))
        return Status::error(StatusCode::InvalidCamera, "prepass: the view matrix is degenerate (eye = target, or up "
                                                        "parallel to the view direction)");

  out.reversedZ = camera.reversedZ;
  out.zeroToOneClip = camera.clipDepth == ClipDepth::ZeroToOne;
  out.flipY = camera.flipY;
  out.clearDepth = camera.reversedZ ? 0.0 : 1.0;

  // Camera space in view units; the frustum widened to the guard band at the same pixel scale.
  const double u = camera.metersToViewUnits;
  const glm::dmat4 modelView = glm::dmat4(glm::dmat3(u)) * viewM;
  glm::dmat4 projection;
  for (int i = 0; i < 16; ++i) projection[i / 4][i % 4] = camera.projection[i];
  glm::dmat4 guard(1.0);
  guard[0][0] = double(camera.width) / double(w);
  guard[1][1] = double(camera.height) / double(h);
  const glm::dmat4 mvp = guard * projection * modelView;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      out.uniforms.mvp[c * 4 + r] = float(mvp[c][r]);
      out.uniforms.modelView[c * 4 + r] = float(modelView[c][r]);
    }
  const bool perspective = camera.kind == ProjectionKind::Perspective;
  out.uniforms.clipInfo = {float(out.model.c0), float(out.model.c1), float(out.model.c2), perspective ? 1.0f : 0.0f};
  out.uniforms.peel = {camera.reversedZ ? -1.0f : 1.0f, camera.reversedZ ? 0.0f : 1.0f,
                       float(options.minSeparation * u), options.cullBackFacesInSecondLayer ? 1.0f : 0.0f};
  return Status::success();
}

void flipRows(std::vector<std::uint32_t>& texels, Extent e) {
  for (std::uint32_t y = 0; y < e.height / 2; ++y)
    std::swap_ranges(texels.begin() + std::ptrdiff_t(y) * e.width, texels.begin() + std::ptrdiff_t(y + 1) * e.width,
                     texels.begin() + std::ptrdiff_t(e.height - 1 - y) * e.width);
}

void flipRows(FloatImage& image) {
  const std::size_t row = std::size_t(image.extent.width) * image.channels;
  for (std::uint32_t y = 0; y < image.extent.height / 2; ++y)
    std::swap_ranges(image.data.begin() + std::ptrdiff_t(y * row), image.data.begin() + std::ptrdiff_t((y + 1) * row),
                     image.data.begin() + std::ptrdiff_t((image.extent.height - 1 - y) * row));
}

}  // namespace sao::prepass::detail
