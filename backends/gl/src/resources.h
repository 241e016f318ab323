// The effect-owned textures, created and destroyed as core's FrameState asks (sao/executor.h): one
// immutable GL_TEXTURE_2D per planned image (csz with its MIP levels; a history two).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "gl_functions.h"
#include "sao/plan.h"

namespace sao::SAO_GL_NS::detail {

GLenum glFormat(gen::Format format);  // GL internal format of an effect image (0 for Depth)

class Resources {
 public:
  explicit Resources(const GlFunctions& gl) : gl_(gl) { slots_.reserve(2 * gen::kResources.size()); }
  ~Resources() { releaseAll(); }
  Resources(const Resources&) = delete;
  Resources& operator=(const Resources&) = delete;

  // The texture(s) of one planned image (a history has two). Textures are bound on `scratchUnit`
  // while they are created (its binding must be saved by the caller). InvalidExtent when a size
  // exceeds maxTextureSize; DriverError when allocation fails (nothing is kept then).
  Status create(const PlannedImage& image, GLuint scratchUnit, GLint maxTextureSize, std::uint64_t& allocations);
  // The texture(s) created for `image` (a new plan's and the current plan's image of one resource
  // exist side by side until FrameState commits: they differ, sameImage()).
  void destroy(const PlannedImage& image);

  // The texture of an owned image; a history (PlannedImage::copies = 2) has two, `copy` 0 and 1.
  GLuint texture(gen::ResourceId id, std::uint32_t copy = 0) const {
    for (const Slot& s : slots_)
      if (s.planned.resource == id) return copy == 0 ? s.texture : s.second;
    return 0;
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
  void release(Slot& s);
  // One immutable texture of img (its levels), labelled; false when its storage failed.
  bool create(const PlannedImage& img, GLenum format, GLuint scratchUnit, const std::string& label, GLuint& out);

  const GlFunctions& gl_;
  std::vector<Slot> slots_;  // one per image; reserved for two per resource, so frames never allocate
  std::uint64_t outputGeneration_ = 0;
};

}  // namespace sao::SAO_GL_NS::detail
