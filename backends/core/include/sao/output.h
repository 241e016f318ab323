// The output image as the engine wants it: its format (one of the formats= the effect declares for
// resource ao: R16F, R8 UNORM, RGBA8 UNORM, RGBA16F) and, for an RGBA output, which channels receive
// the ambient visibility A. The other channels are left untouched: the final pass loads each texel
// and stores it back with only the selected channels replaced (read-modify-write), so an engine can
// pack A next to its own data (e.g. into the alpha of a material texture).
//
// What each format holds (identically on GL, Vulkan and the CPU reference in Float precision):
//  - R16F, RGBA16F: A clamped to [0, 1] and rounded to the nearest binary16 value (ties away from
//    zero, sao_round_to_half);
//  - R8, RGBA8 (UNORM): A clamped to [0, 1] and rounded to the nearest multiple of 1/255, halves
//    up: the stored byte is floor(A * 255 + 0.5), computed in the shader in binary32, so the
//    store's own float-to-unorm rounding (implementation-defined) cannot change it.
#pragma once
#include <cstdint>
#include <span>
#include <string>

#include "sao/status.h"
#include "sao_effect.h"

namespace sao {

// How the channels the mask selects take A. Replace (the default) stores A. Multiply stores the
// texel's own value times A: the apply step, AO multiplied into an existing target (a lit colour
// buffer, best before tone mapping since the product is taken on the stored values; or an
// occlusion texture, e.g. baked AO in an R8 channel), as HBAO+'s multiply blend mode, with no pass
// of the engine's own. The product is rounded once as the format holds it (binary16 of either sign,
// or a multiple of 1/255 clamped to [0, 1]); an infinite or NaN channel is stored back unchanged.
// It needs the caller's output (an effect-owned one holds nothing to multiply) and makes the final
// pass load every texel (as a mask that keeps channels does).
enum class OutputBlend : std::uint8_t { Replace = 0, Multiply = 1 };
static_assert(int(OutputBlend::Replace) == gen::SAO_OUTPUT_BLEND_REPLACE &&
              int(OutputBlend::Multiply) == gen::SAO_OUTPUT_BLEND_MULTIPLY);
// "replace" / "multiply".
const char* toString(OutputBlend blend);
// Ok for Replace, or for Multiply with the caller's output; otherwise InvalidInput naming the blend
// (and an unknown value), prefixed by `who`.
Status checkOutputBlend(OutputBlend blend, bool userOutput, const char* who);

// Channel bits of an output mask.
inline constexpr std::uint32_t kChannelR = 1, kChannelG = 2, kChannelB = 4, kChannelA = 8;
// Every channel the output's format has (the default): R of a one-channel output, RGBA of an RGBA one.
inline constexpr std::uint32_t kAllChannels = kChannelR | kChannelG | kChannelB | kChannelA;

// The formats the effect can write its output in (resource ao's formats=), the default first.
std::span<const gen::Format> outputFormats();
bool isOutputFormat(gen::Format format);
// Channels a format has (1, 2 or 4; Depth 1).
std::uint32_t channelCount(gen::Format format);
// Lower-case name as the effect writes it ("r16f", "rgba8", ...).
const char* formatName(gen::Format format);

// Ok when `mask` is kAllChannels or a non-empty set of channels `format` has (R only for R8 / R16F);
// otherwise InvalidInput naming the mask and the format's channels, prefixed by `who`.
Status checkOutputChannels(gen::Format format, std::uint32_t mask, const char* who);
// The parameter block's output_mask for a checked mask: kAllChannels stays 15 (every channel the
// format has; a one-channel image drops G, B and A).
std::int32_t outputMaskParam(std::uint32_t mask);
// Whether the final pass reads the output's previous texels: a checked mask that leaves some channel
// of `format` untouched, or a Multiply blend (the Vulkan backend then keeps the image's contents
// across its layout transition).
bool keepsChannels(gen::Format format, std::uint32_t mask, OutputBlend blend = OutputBlend::Replace);

// "r16f, r8, rgba8, rgba16f": for messages that name the supported list.
std::string outputFormatList();

}  // namespace sao
