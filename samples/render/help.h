// The parts of `sao-render --help` generated from metadata rather than written by hand.
#pragma once
#include <string>

namespace sao::render {

// Every setting with its type, range, unit ("unitless" when the metadata gives none), default
// and description, from the effect's settings metadata (effect/sao.glsl).
std::string settingsHelp();

// How a depth EXR carries its camera: the sao.* header attributes of sao/io.h.
std::string depthExrHelp();

// Which depth values are warned about as read with the wrong convention, and which cannot be
// told (sao/samples/depth_convention.h).
std::string depthConventionHelp();

}  // namespace sao::render
