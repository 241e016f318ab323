// Settings + camera -> the shaders' parameter block. Pure, computed in double, rounded once.
#pragma once
#include <cstdint>

#include "sao/camera.h"
#include "sao/settings.h"

namespace sao {

using ParamBlock = gen::SaoParams;

// What the depth input holds.
enum class DepthEncoding : std::uint8_t {
  Hardware,  // window-space depth in [0, 1] (D16, D24, D32F), per the camera's conventions
  LinearZ,   // R32F camera-space z (negative in front of the camera), view units
};

// The number of csz MIP levels the largest projected radius can select: 1 + clamp(floor(log2 r'max)
// - log2 q', 0, ...), r'max = r S' / near (perspective) or r S' (orthographic); 1 without the hierarchy.
std::uint32_t mipLevelsNeeded(const Settings& settings, const Camera& camera, const DepthModel& model);

// Fills every member of the block (docs/effect-math.md, section 2). Validates settings and camera
// (also its normals encoding: a world-space one needs viewRotation, which must be a rotation).
Status computeConstants(const Settings& settings, const Camera& camera, DepthEncoding encoding, ParamBlock& out);
// The frame's spiral (sao/spiral.h, frameSpiral) into the block: frame_phase and
// frame_alpha_offset. computeConstants leaves frame 0's; backends set the caller's frame index per
// render / record.
void setFrameIndex(ParamBlock& block, std::uint32_t frameIndex);
// The previous frame's camera into the block's temporal members (prev_from_cur_*, prev_proj_info,
// history_valid = 1), or none (identity, this camera's proj_info, history_valid = 0) for null.
// Both cameras must be valid and carry Camera::view (computeConstants checks `current`; the
// caller, sao/temporal.h, checks `previous`).
void setPreviousFrame(ParamBlock& block, const Camera& current, const Camera* previous);
// proj_info (eq. 3 in csz texel coordinates, the guard band folded in) of a valid camera.
gen::Float4 projInfo(const Camera& camera);

}  // namespace sao
