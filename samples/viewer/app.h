// The viewer's main loop: window, backend, ImGui, scene, camera, panel, reference.
#pragma once
#include "options.h"

namespace sao::viewer {

// Returns the process exit status (see --help).
int runViewer(const Options& options);

}  // namespace sao::viewer
