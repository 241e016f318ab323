// The OpenGL composite: shaders/composite.frag on a fullscreen triangle into the default
// framebuffer, reading the depth, the effect's AO and intermediates and the reference.
#pragma once
#include <epoxy/gl.h>

#include "sao/image.h"
#include "viewer_types.h"

namespace sao::viewer {

struct GlCompositeInputs {
  GLuint depth = 0;  // the prepass depth (with the guard band)
  GLuint ao = 0;     // 0: the effect failed, shown as white
  GLuint aoRaw = 0;  // 0: not planned
  GLuint csz = 0;    // 0: not planned
  GLuint aoReduced = 0;  // split-resolution: the reduced-resolution AO (ao is the full one); 0: white
};

class GlComposite {
 public:
  GlComposite() = default;
  ~GlComposite();
  GlComposite(const GlComposite&) = delete;
  GlComposite& operator=(const GlComposite&) = delete;

  Status init();
  void setReference(const FloatImage* reference);  // 1 channel; null: forget it
  void draw(const CompositeParams& params, const GlCompositeInputs& in, int width, int height);

 private:
  GLuint program_ = 0, vao_ = 0, ubo_ = 0, nearest_ = 0, nearestMip_ = 0, white_ = 0, reference_ = 0;
};

}  // namespace sao::viewer
