// The effect-owned textures, allocated from the plan: one immutable GL_TEXTURE_2D per planned
// image (csz with its MIP levels) plus single-level views of the MIP chains (bindings that see one level).
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
  GLuint levelView(gen::ResourceId id, std::uint32_t level) const;  // single-level view, 0 if none
  void releaseAll();

 private:
  struct Slot {
    GLuint texture = 0;
    GLuint second = 0;          // a history's second copy
    PlannedImage planned;       // what the texture was allocated for
    std::vector<GLuint> views;  // views[m]: level m alone (chains only)
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
