// Compute programs built from the generated GLSL 4.30 blobs (gen::glslSource; on ES the GLSL ES 3.10
// ones, gen::esslSource), compiled on first use and cached per blob. No other shader text is ever compiled.
#pragma once
#include <cstdint>
#include <vector>

#include "gl_functions.h"
#include "sao_effect.h"

namespace sao::SAO_GL_NS::detail {

class Programs {
 public:
  explicit Programs(const GlFunctions& gl) : gl_(gl), programs_(kEs ? gen::kEsslBlobCount : gen::kGlslBlobCount, 0) {}
  ~Programs();
  Programs(const Programs&) = delete;
  Programs& operator=(const Programs&) = delete;

  // The program of a pass variant; DriverError with the driver's log if it does not compile/link.
  Status get(const gen::PassInfo& pass, const gen::PassVariantInfo& variant, GLuint& program,
             std::uint64_t& compiled);
  // The program get() made for a variant; 0 if none.
  GLuint find(const gen::PassVariantInfo& variant) const {
    const std::uint32_t blob = sourceBlob(variant);
    return blob < programs_.size() ? programs_[blob] : 0;
  }
  // The variant's source blob on this API (on ES an out-of-range index where it has none).
  static std::uint32_t sourceBlob(const gen::PassVariantInfo& variant) {
    return kEs ? (variant.esslBlob < 0 ? ~0u : std::uint32_t(variant.esslBlob)) : variant.glslBlob;
  }

 private:
  const GlFunctions& gl_;
  std::vector<GLuint> programs_;
};

}  // namespace sao::SAO_GL_NS::detail
