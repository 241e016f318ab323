#include "sao/samples/backend_runner.h"

#include "runners.h"

namespace sao::samples {

gen::Format runnerOutputFormat(const Settings& settings) {
  return settings.bent_normals ? gen::Format::RGBA16F : gen::kResources[std::size_t(gen::ResourceId::ao)].format;
}

void splitOutput(FloatImage output, RunOutputs& out) {
  if (output.channels != 4) {
    out.ao = std::move(output);
    out.bentNormals = {};
    return;
  }
  out.ao = FloatImage(output.extent, 1);
  out.bentNormals = FloatImage(output.extent, 3);
  for (std::uint32_t y = 0; y < output.extent.height; ++y)
    for (std::uint32_t x = 0; x < output.extent.width; ++x) {
      for (std::uint32_t c = 0; c < 3; ++c) out.bentNormals.at(x, y, c) = output.at(x, y, c);
      out.ao.at(x, y) = output.at(x, y, 3);
    }
}

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
