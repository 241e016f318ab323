#include "resources.h"

#include "sao/schedule.h"

#include <string>

namespace sao::SAO_GL_NS::detail {

GLenum glFormat(gen::Format format) {
  // On ES an image takes the format the effect's `target gles` rule gives it.
  const gen::FormatInfo& f = gen::formatInfo(kEs ? gen::glesStorageFormat(format) : format);
  return f.colour ? GLenum(f.glInternalFormat) : 0;  // depth is never an effect image
}

void Resources::release(Slot& s) {
  if (s.texture) gl_.DeleteTextures(1, &s.texture);
  if (s.second) gl_.DeleteTextures(1, &s.second);
  s = Slot{};
}

void Resources::releaseAll() {
  for (Slot& s : slots_) release(s);
  slots_.clear();
}

bool Resources::create(const PlannedImage& img, GLenum format, GLuint scratchUnit, const std::string& label, GLuint& out) {
  gl_.GenTextures(1, &out);
  gl_.ActiveTexture(GL_TEXTURE0 + scratchUnit);
  gl_.BindTexture(GL_TEXTURE_2D, out);
  gl_.TexStorage2D(GL_TEXTURE_2D, GLsizei(img.mipLevels), format, GLsizei(img.extent.width), GLsizei(img.extent.height));
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, img.mipLevels > 1 ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  // Allocation failures are detected without glGetError (which would swallow the caller's errors):
  // a texture whose storage could not be allocated is not immutable.
  GLint immutable = 0;
  gl_.GetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_IMMUTABLE_FORMAT, &immutable);
  gl_.BindTexture(GL_TEXTURE_2D, 0);
  gl_.label(GL_TEXTURE, out, label);
  return immutable != 0;
}

Status Resources::create(const PlannedImage& img, GLuint scratchUnit, GLint maxTextureSize, std::uint64_t& allocations) {
  Slot s;
  const auto& info = gen::kResources[static_cast<std::size_t>(img.resource)];
  const std::string name = std::string(info.name);
  const GLenum format = glFormat(img.format);
  if (format == 0) return Status::error(StatusCode::UnsupportedFormat, std::string(kApiName) + ": image '" + name + "' has no GL format");
  if (img.extent.width > std::uint32_t(maxTextureSize) || img.extent.height > std::uint32_t(maxTextureSize))
    return Status::error(StatusCode::InvalidExtent,
                         std::string(kApiName) + ": image '" + name + "' is " + std::to_string(img.extent.width) + "x" +
                             std::to_string(img.extent.height) + ", above GL_MAX_TEXTURE_SIZE " +
                             std::to_string(maxTextureSize));
  if (info.kind == gen::ResourceKind::Output) ++outputGeneration_;  // a new texture object serves aoTexture()
  bool immutable = create(img, format, scratchUnit, "sao " + name, s.texture);
  if (img.copies > 1) immutable = create(img, format, scratchUnit, "sao " + name + " (2)", s.second) && immutable;
  ++allocations;
  if (!immutable) {
    release(s);
    return Status::error(StatusCode::DriverError, std::string(kApiName) + ": allocating image '" + name + "' (" +
                                                      std::to_string(img.extent.width) + "x" +
                                                      std::to_string(img.extent.height) + ", " +
                                                      std::to_string(img.mipLevels) + " levels) failed (out of memory?)");
  }
  s.planned = img;
  slots_.push_back(s);
  return Status::success();
}

void Resources::destroy(const PlannedImage& image) {
  for (auto it = slots_.begin(); it != slots_.end(); ++it) {
    if (it->planned.resource != image.resource || !sameImage(it->planned, image)) continue;
    if (gen::kResources[static_cast<std::size_t>(image.resource)].kind == gen::ResourceKind::Output)
      ++outputGeneration_;  // the owned output goes away
    release(*it);
    slots_.erase(it);
    return;
  }
}

}  // namespace sao::SAO_GL_NS::detail
