// The effect's inputs as the screen-space references (c) and (d) take them (converged.cpp,
// screen_visibility.cpp): checked against the camera as a backend checks them, the parameter block
// the effect would use, and csz level 0 in double. Includes sao_math.h: compile with
// -ffp-contract=off (CMakeLists.txt).
#pragma once
#include <string>

#include "sao/camera.h"
#include "sao/image.h"
#include "sao/raytrace/converged.h"
#include "sao/settings.h"
#include "sao/status.h"
#include "sao_math.h"

namespace sao::raytrace::detail {

// InvalidInput "<who>: ..." for a missing depth, or a depth, second layer or normals whose extent or
// format disagree with the camera (viewport + 2 * guard band); the core's error for bad settings or
// camera. Fills `block` as computeConstants does for the depth's encoding.
Status checkScreenInputs(const std::string& who, const Settings& settings, const Camera& camera,
                         const ConvergedInputs& in, gen::ParamBlock& block);

// Level 0 of csz in double, as the linear_z pass computes it.
cpu::detail::Image<double> linearZ(const DepthImage& depth, const cpu::detail::Block<double>& P);

}  // namespace sao::raytrace::detail
