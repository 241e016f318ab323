#include "sao/samples/backend_runner.h"

#include "runners.h"

namespace sao::samples {

Status createBackend(std::string_view name, std::unique_ptr<BackendRunner>& out) {
  if (name == "cpu" || name == "cpu-double") {
    out = makeCpuRunner(name == "cpu-double");
    return Status::success();
  }
  if (name == "gl") {
#ifdef SAO_SAMPLES_HAVE_GL
    return makeGlRunner(out);
#else
    return Status::error(StatusCode::DriverError, "this program was built without the OpenGL backend");
#endif
  }
  if (name == "vulkan") {
#ifdef SAO_SAMPLES_HAVE_VULKAN
    return makeVulkanRunner(out);
#else
    return Status::error(StatusCode::DriverError, "this program was built without the Vulkan backend");
#endif
  }
  if (name == "auto") {
    for (const char* candidate : {"gl", "vulkan"}) {
      if (createBackend(candidate, out).ok()) return Status::success();
    }
    out = makeCpuRunner(false);
    return Status::success();
  }
  return checkBackendName(name);
}

Status checkBackendName(std::string_view name) {
  for (std::string_view known : {"gl", "vulkan", "cpu", "cpu-double", "auto"})
    if (name == known) return Status::success();
  return Status::error(StatusCode::InvalidInput,
                       "unknown backend '" + std::string(name) + "' (expected gl, vulkan, cpu, cpu-double or auto)");
}

bool isBackendBuiltIn(std::string_view name) {
  if (name == "cpu" || name == "cpu-double") return true;
#ifdef SAO_SAMPLES_HAVE_GL
  if (name == "gl") return true;
#endif
#ifdef SAO_SAMPLES_HAVE_VULKAN
  if (name == "vulkan") return true;
#endif
  return false;
}

}  // namespace sao::samples
