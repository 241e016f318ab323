// createPrepass: the programs pick a prepass by name without caring which APIs were built.
#include "sao/prepass/prepass.h"

#ifdef SAO_PREPASS_HAVE_GL
#include "sao/prepass/gl_prepass.h"
#endif
#ifdef SAO_PREPASS_HAVE_VULKAN
#include "sao/prepass/vk_prepass.h"
#endif

namespace sao::prepass {

namespace {

Status createNamed(std::string_view name, std::unique_ptr<Prepass>& out) {
  if (name == "gl") {
#ifdef SAO_PREPASS_HAVE_GL
    std::unique_ptr<GlPrepass> gl;
    if (Status s = GlPrepass::create(gl, GlPrepassOptions{true, false}); !s) return s;
    out = std::move(gl);
    return Status::success();
#else
    return Status::error(StatusCode::DriverError, "the OpenGL prepass is not built into this program (SAO_BUILD_GL=OFF)");
#endif
  }
  if (name == "vulkan") {
#ifdef SAO_PREPASS_HAVE_VULKAN
    std::unique_ptr<VkPrepass> vk;
    if (Status s = VkPrepass::create(vk); !s) return s;
    out = std::move(vk);
    return Status::success();
#else
    return Status::error(StatusCode::DriverError, "the Vulkan prepass is not built into this program (SAO_BUILD_VULKAN=OFF)");
#endif
  }
  return Status::error(StatusCode::InvalidInput, "unknown prepass '" + std::string(name) + "' (gl, vulkan or auto)");
}

}  // namespace

Status createPrepass(std::string_view name, std::unique_ptr<Prepass>& out) {
  out.reset();
  if (name != "auto") return createNamed(name, out);
  std::string why;
  for (std::string_view candidate : {"gl", "vulkan"}) {
    Status s = createNamed(candidate, out);
    if (s) return s;
    why += (why.empty() ? "" : "; ") + std::string(candidate) + ": " + s.message;
  }
  return Status::error(StatusCode::DriverError, "no rasterising prepass could start (" + why + ")");
}

}  // namespace sao::prepass
