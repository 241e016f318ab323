// Compute programs built from the generated GLSL 4.30 blobs (gen::glslSource), compiled on first
// use and cached per blob. No other shader text is ever compiled.
#pragma once
#include <cstdint>
#include <vector>

#include "gl_functions.h"
#include "sao_effect.h"

namespace sao::gl::detail {

class Programs {
 public:
  explicit Programs(const GlFunctions& gl) : gl_(gl), programs_(gen::kGlslBlobCount, 0) {}
  ~Programs();
  Programs(const Programs&) = delete;
  Programs& operator=(const Programs&) = delete;

  // The program of a pass variant; DriverError with the driver's log if it does not compile/link.
  Status get(const gen::PassInfo& pass, const gen::PassVariantInfo& variant, GLuint& program,
             std::uint64_t& compiled);
  // The program get() made for a variant; 0 if none.
  GLuint find(const gen::PassVariantInfo& variant) const {
    return variant.glslBlob < programs_.size() ? programs_[variant.glslBlob] : 0;
  }

 private:
  const GlFunctions& gl_;
  std::vector<GLuint> programs_;
};

}  // namespace sao::gl::detail
