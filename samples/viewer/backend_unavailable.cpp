// Backends left out of this build (SAO_BUILD_GL / SAO_BUILD_VULKAN off) say so.
#include "backend.h"

namespace sao::viewer {

#if !defined(SAO_VIEWER_HAVE_GL)
Status createGlBackend(Window&, const BackendOptions&, std::unique_ptr<Backend>&) {
  return Status::error(StatusCode::DriverError, "this sao-viewer was built without the OpenGL backend");
}
#endif

#if !defined(SAO_VIEWER_HAVE_VULKAN)
Status createVulkanBackend(Window&, const BackendOptions&, std::unique_ptr<Backend>&) {
  return Status::error(StatusCode::DriverError, "this sao-viewer was built without the Vulkan backend");
}
#endif

}  // namespace sao::viewer
