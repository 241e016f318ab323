// sao::cpu — the CPU reference backend: the compute passes of effect/sao.glsl re-implemented in
// C++, operation for operation (docs/effect-math.md), so that the OpenGL and Vulkan backends can
// be compared with it pixel by pixel. Each pass's C++ lives beside its GLSL (effect/cpu/); the
// backend runs core's schedule through them (docs/adding-a-pass.md). Compiled into this static
// library, so no header here needs them.
//
// Two precisions:
//
//  * Precision::Float mimics the GPU. Every `+ - * /` is one binary32 operation in the order the
//    GLSL writes it (the library is compiled with -ffp-contract=off, so nothing is fused into an
//    FMA), block members are used as the float values the shaders see, and the output is rounded
//    to binary16 exactly like sao_round_to_half. csz (every level, both layers), ao_raw.y and the
//    blur passes (given the same input) are expected to be bit-identical to a conforming GPU;
//    ao_raw.x may differ by a few ulps where the GPU's own accuracy differs from ours:
//      - cos / sin (GLSL: absolute error <= 2^-11 on [-pi, pi]; here std::cos/std::sin(float),
//        glibc's correctly rounded-or-nearly results),
//      - division (GLSL: 2.5 ulp; here IEEE division),
//      - inversesqrt (GLSL: 2 ulp; here 1.0f / std::sqrt),
//      - pow (only when contrast != 1; GLSL: as exp2(y * log2(x)); here std::pow),
//      - FMA contraction the GPU compiler may apply to a*b + c (we never contract),
//      - the unorm-to-float conversion of D16/D24 texels: here float(v) * float(1 / (2^n - 1)),
//        which is what Mesa's llvmpipe and lavapipe do (checked bit for bit); a GPU that rounds
//        v / (2^n - 1) correctly reads about half of the D24 texels one ulp differently, which
//        moves csz by ~1e-6 relative and A by a few 1e-4 at most.
//    A tap address int(h * u) can then flip by one pixel where h * u is within an ulp of an
//    integer, which moves one term of one pixel.
//    Measured against Mesa 22.3 llvmpipe (GL 4.5, the generated GLSL) on 16 configurations
//    (perspective standard / reversed / infinite, y-flipped, orthographic, D16 / D24 / D32F /
//    linear z, user normals uploaded as halfBits(), two layers, no hierarchy, odd sizes, s = 1 /
//    7 / 64, contrast != 1, blur radius 0 / 3 / 8): csz, ao_raw.y and the final ao bit-identical,
//    ao_raw.x within 4e-7.
//
//  * Precision::Double evaluates the same formulas in the same order in double, starting from the
//    same block values (each float member widened to double) and the same texel values (depth
//    decoded in double, normals rounded to binary16 as the rgba16f texture holds them). The hash
//    and the spiral turns are integer and identical; the tap addresses int(h * u) and MIP levels
//    findMSB(int(h)) may differ by one where the value is within float rounding of an integer. The
//    intermediate images are kept in double and only rounded to float when stored into Result;
//    the final binary16 rounding is skipped (Result::ao holds the unrounded A).
//
// Every pass runs in parallel over rows (ao_sample over rows of work groups); every output texel
// is a pure function of its inputs, so results are bit-identical for any thread count.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "sao/camera.h"
#include "sao/image.h"
#include "sao/output.h"
#include "sao/plan.h"
#include "sao/settings.h"
#include "sao/status.h"
#include "sao/timing.h"

namespace sao::cpu {

enum class Precision { Double, Float };

const char* toString(Precision precision);

struct Inputs {
  // Required. Hardware depth (D16 / D24 / D32F, per the camera's conventions) or LinearZ (R32F
  // camera-space z, then DepthEncoding::LinearZ is used). The region read is the plan's input
  // extent (viewport + 2 * guard band) from `offset` on; the image may be larger.
  const DepthImage* depth = nullptr;
  // Optional second depth layer (deep G-buffer, TWO_LAYER): same format as depth, the same region.
  const DepthImage* depth2 = nullptr;
  // Optional normals (NORMALS_SUPPLIED): 4 channels, encoded as Camera::normalsEncoding says
  // (camera-space .xyz by default, components in [-1, 1]; world space and octahedral .xy too),
  // the same region as depth. They are read as the rgba16f texture would hold them: each
  // component rounded to the nearest binary16 value (ties to even, see quantizeHalf() and
  // halfBits()).
  const FloatImage* normals = nullptr;
  // Optional: where the region starts in depth, depth2 and normals (shared; row 0 first, as the
  // GPU backends' Inputs::region). Unset, every input must be exactly the region's size; a region
  // outside an image is refused, never clamped.
  std::optional<Offset> region{};
  // The output as the engine wants it (sao/output.h): its format (R16F, R8, RGBA8 or RGBA16F) and
  // the channels that receive A. Result::ao then has the format's channel count, and in Float
  // precision holds what the GPU backends store (binary16 values or multiples of 1/255).
  gen::Format outputFormat = gen::Format::R16F;
  std::uint32_t outputChannels = kAllChannels;
  // How those channels take A (sao/output.h): Replace, or Multiply (the texel's value times A; needs
  // `output` below, refused without it as the GPU backends refuse it without the caller's output).
  OutputBlend outputBlend = OutputBlend::Replace;
  // The frame's number (sao::frameSpiral): frame k turns and shifts every pixel's spiral, as the
  // GPU backends' Inputs::frameIndex; frame 0 is the paper's spiral.
  std::uint32_t frameIndex = 0;
  // Optional: the output's contents before the run (the viewport's extent, the format's channel
  // count), kept in the channels outputChannels leaves out, as a GPU backend keeps the caller's
  // texels (and multiplied in the others with OutputBlend::Multiply). A mask that keeps channels
  // and the multiply blend need it (refused without, as the GPU backends refuse them without the
  // caller's output: sao::checkFrameOutput).
  const FloatImage* output = nullptr;
  // Temporal accumulation (the `temporal` setting): the history the previous run wrote
  // (Result::images[history][0]: 4 channels, the planned history extent) and the camera it ran
  // with (which needs Camera::view, like this run's camera). Both or neither: without them this
  // run starts the history again from its own frame (history_valid = 0), as a GPU backend does after
  // a reset. The CPU reference is stateless: the caller carries the history from run to run.
  const FloatImage* history = nullptr;
  const Camera* previousCamera = nullptr;
  // Optional, with the temporal setting: motion vectors (MOTION_VECTORS), two or more channels, the
  // depth's region: .xy the offset in pixels from each texel to where its surface was in the
  // previous frame (previous = current + motion), read as the rg16f texture holds them (each
  // rounded to binary16). The history is then found there instead of through the cameras.
  const FloatImage* motion = nullptr;
  // Any other colour input the effect declares (a kind=input resource that is not depth, depth2,
  // normals or motion: the walkthrough's ao_scale), by resource id: at least as many channels as
  // its format=, the depth's region. A pass's oracle reads it through colourInput() below, as the
  // texture would hold it (its own rounding). Every other entry must stay null.
  std::array<const FloatImage*, gen::kResources.size()> moreInputs{};
};

// The image of colour input `id`: Inputs::normals, Inputs::motion or Inputs::moreInputs[id].
const FloatImage* colourInput(const Inputs& in, gen::ResourceId id);

struct Options {
  Precision precision = Precision::Double;
  unsigned threads = 0;      // 0 = std::thread::hardware_concurrency()
  bool measureTime = false;  // fill Result::timings with each pass's wall time (CpuClock)
};

struct Result {
  Plan plan;              // what ran (passes, variants, csz levels, aliasing)
  gen::SaoParams params;  // the block the passes used (as computeConstants filled it)
  std::vector<FloatImage> csz, csz2;  // one image per level (1 channel); csz2 only with depth2
  FloatImage aoRaw;    // 2 channels: A after the 2x2 reconstruction, key z (+0.0 = sky); empty when
                       // the plan has none (ao_sample_output wrote the output: no blur, full res.)
  FloatImage ao;       // the output, Inputs::outputFormat's channels: final A (Float: as that format
                       // rounds it; Double: unrounded) in Inputs::outputChannels, the rest kept
  // Every other image the plan allocates, by gen::ResourceId, one FloatImage per level: what a
  // pass added to the effect writes (the walkthrough's ao_half). Empty for the images above, for
  // inputs and for images the plan does not allocate.
  std::array<std::vector<FloatImage>, gen::kResources.size()> images;
  Timings timings;     // method None unless Options::measureTime; one entry per planned pass
};

// Validates the inputs against the settings and camera, fills the block with computeConstants,
// builds the plan with PlanInputs{encoding, normals != nullptr, depth2 != nullptr} and runs exactly
// the planned passes in order (makeSchedule's dispatches). On error `out` is left
// default-constructed and the Status names the problem (InvalidInput for missing or mismatched
// inputs or a planned pass the effect gives no C++ for, UnsupportedFormat for unknown formats,
// InvalidSetting / InvalidCamera / InvalidExtent from the core); bad input never asserts or crashes.
Status run(const Settings& settings, const Camera& camera, const Inputs& inputs, const Options& options,
           Result& out);

// Half-float helpers live in core (sao/image.h); kept here under their first names.
using sao::halfBits;
using sao::quantizeHalf;

// sao_round_to_half of sao_blur.glsl: x clamped to [0, 1] and rounded to the nearest binary16
// value with ties away from zero, using only exact operations.
float roundToHalfAsShader(float x);

// sao_round_to_unorm8 of sao_output.glsl (R8 / RGBA8 outputs): x clamped to [0, 1], rounded to the
// nearest multiple of 1/255 with halves up, floor(x * 255 + 0.5) / 255 in binary32.
float roundToUnorm8AsShader(float x);
// sao_output_multiply of sao_output.glsl (OutputBlend::Multiply, Float precision): the channel c
// times A clamped to [0, 1], rounded once as the format holds it (unorm8: roundToUnorm8AsShader;
// else the nearest binary16 of either sign, ties away from zero, not clamped); an infinite or NaN
// c is returned as it is.
float outputMultiplyAsShader(float c, float a, bool unorm8);

}  // namespace sao::cpu
