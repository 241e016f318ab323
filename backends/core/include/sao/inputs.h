// What the effect accepts for each of its inputs, from effect/'s kind=input declarations: one
// contract every backend applies by resource id, so an input declared in the effect needs no
// backend code (docs/adding-a-pass.md, section 6).
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "sao/camera.h"
#include "sao/status.h"
#include "sao_effect.h"

namespace sao {

// format=depth: the API's depth formats or linear camera-space z (R32F); every depth input of a
// frame holds the same encoding as `depth`.
bool isDepthInput(gen::ResourceId input);
// Declared without when=: every frame supplies it (the depth).
bool isRequiredInput(gen::ResourceId input);
// A select=multisampled: variant reads it: its image may have several samples per texel.
bool mayBeMultisampled(gen::ResourceId input);

// The effect's format of an API format: the entry of gen::kFormatInfo whose GL internal format
// (or VkFormat) it is; none for a format the table does not hold.
std::optional<gen::Format> formatOfGl(std::uint32_t glInternalFormat);
std::optional<gen::Format> formatOfVk(std::uint32_t vkFormat);

// A colour input's texels: Ok, or UnsupportedFormat "<image> is <format>; <name> must be <list>"
// when formats= lists others, or when the image has fewer channels than the effect reads (normals:
// per Camera::normalsEncoding, checkNormalsChannels; others: format='s). `format` is the image's
// effect format (none: not in the table), `channels` its colour channels (0: not a colour format
// the API reads as float); `image` names it as the backend does ("sao::gl: the motion texture 7"),
// `formatText` its format, `listName` one of the effect's formats in the API's names, `noun` what
// the API calls the image ("texture", "format"). Allocates only to build an error: a per-frame
// caller builds `image` and `formatText` lazily, so pass them through inputNeedsMessage() first.
Status checkColourInput(gen::ResourceId input, std::optional<gen::Format> format, std::uint32_t channels,
                        const Camera& camera, const std::string& image, const std::string& formatText,
                        std::string (*listName)(gen::Format), const char* noun);
// Whether checkColourInput would refuse (it is Ok without building anything otherwise).
bool colourInputRefused(gen::ResourceId input, std::optional<gen::Format> format, std::uint32_t channels,
                        const Camera& camera);

}  // namespace sao
