// Factories of the backends compiled into the samples (the GL and Vulkan ones only when built).
#pragma once
#include <memory>

#include "sao/samples/backend_runner.h"

namespace sao::samples {

// Float mode mimics the GPU; double mode is the precision oracle.
std::unique_ptr<BackendRunner> makeCpuRunner(bool doublePrecision);
#ifdef SAO_SAMPLES_HAVE_GL
Status makeGlRunner(std::unique_ptr<BackendRunner>& out);
#endif
#ifdef SAO_SAMPLES_HAVE_VULKAN
Status makeVulkanRunner(std::unique_ptr<BackendRunner>& out);
#endif

}  // namespace sao::samples
