// The effect-owned textures, allocated from the plan: one immutable GL_TEXTURE_2D per planned
// image (csz with its MIP levels; a history two).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "gl_functions.h"
#include "sao/plan.h"

namespace sao::gl::detail {

GLenum glFormat(gen::Format format);  // GL internal format of an effect image (0 for Depth)

class Resources {
 public:
  explicit Resources(const GlFunctions& gl) : gl_(gl) {}
  ~Resources() { releaseAll(); }
  Resources(const Resources&) = delete;
  Resources& operator=(const Resources&) = delete;

  // Makes the owned images match plan.images: images whose format, extent or level count is
  // unchanged keep their texture; changed ones are recreated, unplanned ones deleted. Textures are
  // bound on `scratchUnit` while they are created (its binding must be saved by the caller).
  // InvalidExtent when a size exceeds maxTextureSize; DriverError when allocation fails.
  Status update(const Plan& plan, GLuint scratchUnit, GLint maxTextureSize, std::uint64_t& allocations);

  // The texture of an owned image; a history (PlannedImage::copies = 2) has two, `copy` 0 and 1.
  GLuint texture(gen::ResourceId id, std::uint32_t copy = 0) const {
    return copy == 0 ? slot(id).texture : slot(id).second;
  }
  // Goes up each time an effect-owned output texture is created or deleted.
  std::uint64_t outputGeneration() const { return outputGeneration_; }
  void releaseAll();

 private:
  struct Slot {
    GLuint texture = 0;
    GLuint second = 0;          // a history's second copy
    PlannedImage planned;       // what the texture was allocated for
  };
  const Slot& slot(gen::ResourceId id) const { return slots_[static_cast<std::size_t>(id)]; }
  void release(Slot& s);
  // One immutable texture of img (its levels), labelled; false when its storage failed.
  bool create(const PlannedImage& img, GLenum format, GLuint scratchUnit, const std::string& label, GLuint& out);

  const GlFunctions& gl_;
  std::array<Slot, gen::kResources.size()> slots_{};
  std::uint64_t outputGeneration_ = 0;
};

}  // namespace sao::gl::detail
