// The API of the OpenGL backends, declared once and included twice: in namespace sao::gl by
// sao/gl/effect.h (OpenGL 4.3) and in sao::gles by sao/gles/effect.h (OpenGL ES 3.1). No include
// guard: SAO_GL_API_NS names the namespace. The contract comments say "GL" for both; where ES
// differs, sao/gles/effect.h says how.
namespace sao::SAO_GL_API_NS {

// The loader the caller already has: eglGetProcAddress, glfwGetProcAddress, SDL_GL_GetProcAddress
// (cast), wglGetProcAddress wrapped to fall back to opengl32.dll for GL 1.1 entry points, ...
using ProcAddress = void (*)();
using GetProcAddressFn = ProcAddress (*)(const char* name);

// GL enums used below, spelled out so that this header needs no GL header.
inline constexpr std::uint32_t kDepthComponent16 = 0x81A5;   // GL_DEPTH_COMPONENT16
inline constexpr std::uint32_t kDepthComponent24 = 0x81A6;   // GL_DEPTH_COMPONENT24
inline constexpr std::uint32_t kDepthComponent32F = 0x8CAC;  // GL_DEPTH_COMPONENT32F
inline constexpr std::uint32_t kDepth24Stencil8 = 0x88F0;    // GL_DEPTH24_STENCIL8
inline constexpr std::uint32_t kDepth32FStencil8 = 0x8CAD;   // GL_DEPTH32F_STENCIL8
inline constexpr std::uint32_t kR32F = 0x822E;               // GL_R32F (linear camera-space z)
inline constexpr std::uint32_t kR16F = 0x822D;               // GL_R16F (the AO output's default)
inline constexpr std::uint32_t kR8 = 0x8229;                 // GL_R8 (an output format)
inline constexpr std::uint32_t kRGBA8 = 0x8058;              // GL_RGBA8 (an output format)
inline constexpr std::uint32_t kRGBA16F = 0x881A;            // GL_RGBA16F (an output format)

// One of your input textures: level 0 of a GL_TEXTURE_2D (the depth also GL_TEXTURE_2D_MULTISAMPLE;
// with Inputs::layer, one layer of a GL_TEXTURE_2D_ARRAY), 0 where you give none. The effect
// queries the texture's real internal format and size; `internalFormat`, when not 0, is what you
// say it holds, and a texture that holds another is refused.
struct InputTexture {
  std::uint32_t texture = 0;
  std::uint32_t internalFormat = 0;
  constexpr InputTexture() = default;
  constexpr InputTexture(std::uint32_t name, std::uint32_t format = 0) : texture(name), internalFormat(format) {}
};
using DepthInput = InputTexture;

// The inputs are the effect's kind=input resources (effect/sao.glsl), one InputTexture each, by
// name (inputs.depth, inputs.normals, ...) or by id (inputs[gen::ResourceId::normals]); every one
// is read over the same region (below). What each accepts, one contract on every backend
// (sao/inputs.h):
//  * depth (required) and depth2 (a second layer, the deep G-buffer): GL_DEPTH_COMPONENT16/24/32F,
//    GL_DEPTH24_STENCIL8, GL_DEPTH32F_STENCIL8 (hardware depth per the Camera's conventions) or
//    GL_R32F (linear camera-space z, negative in front of the camera, view units); depth2 holds the
//    same encoding as depth. Depth values (sao/image.h): GL clamps depth textures to [0, 1] (and
//    -0.0 to +0.0), so they always hold valid hardware depth; R32F linear z that is NaN, +-Inf, +-0
//    or positive is sky. Only depth may be multisampled (GL_TEXTURE_2D_MULTISAMPLE, read per
//    Camera::depthSamplePolicy).
//  * an input whose declaration lists formats= (motion: GL_RG16F recommended, GL_RG32F, GL_RGBA16F,
//    GL_RGBA32F): one of those.
//  * any other (normals): a float or snorm colour texture (GL_RGBA16F, GL_RGBA32F, GL_RGB16F,
//    GL_RGB32F, GL_RGBA8_SNORM, GL_RGBA16_SNORM, GL_RG16F, GL_RG32F, GL_RG8_SNORM, GL_RG16_SNORM)
//    with the channels the effect reads: normals, encoded as Camera::normalsEncoding says
//    (camera-space .xyz by default, components in [-1, 1]), need three or four (GL_RGBA16F
//    recommended), two for the octahedral encodings, which read .xy; fewer is refused
//    (UnsupportedFormat naming both).
// Motion vectors (with the temporal setting): .xy the offset in pixels from each texel to where its
// surface was in the previous frame (previous = current + motion, in the depth's row order); the
// history of a moving object is then found where it was. Refused without the temporal setting (an
// input nothing would read).
struct Inputs : gen::InputSet<InputTexture> {
  // Optional: the inputs hold the camera's image as a region of larger textures (dynamic
  // resolution). The texel (x along a row, y in rows from row 0, i.e. storage order) of depth,
  // depth2 and normals (they share it) that holds the guard band's first corner. Unset, every
  // input must be exactly the region's size. A region that does not lie inside every texture given
  // is refused (InvalidInput naming the offset, the extent and the texture's size), never clamped.
  // Changing it does not plan again.
  std::optional<Offset> region{};
  // Optional output: your texture of the viewport size whose level 0 receives A, in GL_R16F,
  // GL_R8, GL_RGBA8 or GL_RGBA16F (sao/output.h says how each rounds A; another format is
  // refused with UnsupportedFormat naming it and this list). 0: the effect writes into a GL_R16F
  // texture it owns (aoTexture()). Must not be one of the inputs.
  std::uint32_t output = 0;
  // Which channels of the output receive A (sao/output.h): kAllChannels (the default: every channel
  // the format has) or a non-empty set of kChannelR/G/B/A it has. The other channels of an RGBA
  // output keep their texels (the final pass loads each texel and stores it back with only these
  // channels replaced), so A can share a texture with your own data. Changing it does not plan again.
  std::uint32_t outputChannels = kAllChannels;
  // How those channels take A (sao/output.h): Replace (the default), or Multiply: each is multiplied
  // by A, the apply step in the effect's final pass (e.g. output = your lit GL_RGBA16F colour target,
  // outputChannels = kChannelR | kChannelG | kChannelB). Multiply needs `output` (InvalidInput
  // without it). Changing it does not plan again.
  OutputBlend outputBlend = OutputBlend::Replace;
  // The frame's number, for an engine that accumulates frames (TAA or its own temporal filter):
  // frame k turns and shifts every pixel's spiral (sao::frameSpiral, sao/spiral.h), so N
  // consecutive frames sample the disk evenly; frame 0 (the default) is the paper's spiral. Count
  // it up by one per frame. Changing it does not plan again.
  std::uint32_t frameIndex = 0;
  // Stereo / multiview: the array layer to read and write when the textures are
  // GL_TEXTURE_2D_ARRAYs (the depth also GL_TEXTURE_2D_MULTISAMPLE_ARRAY) with immutable storage
  // (glTexStorage3D). Render each eye with its own camera and layer on ONE effect: programs and
  // intermediate textures are shared, and a camera that plans like the previous one (the other eye
  // of a symmetric pair: the same viewport, guard band and csz levels) does not plan again.
  // Every texture given must then be an array with more than `layer` layers; with GL_TEXTURE_2D
  // textures it must be 0. Needs GL 4.5 (DSA). The effect reads a layer through a texture view it
  // creates and deletes within render() (a name, no storage); the layers' texture parameters are
  // the views' own, so the caller's are never touched.
  std::uint32_t layer = 0;
  // Temporal accumulation (the `temporal` setting; sao/temporal.h says when the history is reused):
  // the effect keeps two history textures and the camera of its last render, and blends each
  // pixel's obscurance with that frame's, reprojected through Camera::view (required then).
  // resetHistory: start again from this frame alone (a camera cut, a teleport). previousCamera:
  // the camera the history was made with, when it is not the one of the effect's last render
  // (null: that one); without the temporal setting both are ignored. The history follows one view:
  // render each eye of a stereo pair with its own effect (layer must be 0 with temporal).
  bool resetHistory = false;
  const Camera* previousCamera = nullptr;
};

struct RenderOptions {
  bool measureTime = false;  // fill timings(): per-pass GPU time (see timing.h for the methods)
};

// Counters for tests and tools.
struct Stats {
  std::uint64_t renders = 0;
  std::uint64_t textureAllocations = 0;  // effect-owned textures created so far
  std::uint64_t programsCompiled = 0;
  // Configurations planned: render() plans again only when the settings, the kinds of input or a
  // plan-changing camera change (sao::cameraKeepsPlan), never for TAA jitter or the other eye.
  std::uint64_t plans = 0;
};

class SAO_GL_API Effect {
 public:
  // Loads the GL entry points, checks the context (GL 4.3 or newer, compute limits) and creates
  // the effect's buffer and samplers. `headerVersion` is the SAO_VERSION of the headers the
  // caller compiled against; a different library version gives VersionMismatch. Never throws.
  static Status create(GetProcAddressFn getProcAddress, std::unique_ptr<Effect>& out,
                       int headerVersion = SAO_VERSION);

  ~Effect();  // deletes the effect's GL objects (the context must be current)
  Effect(const Effect&) = delete;
  Effect& operator=(const Effect&) = delete;

  // Runs the planned passes: core's sao::FrameState (sao/executor.h) plans, keeps and fills the
  // block, the effect executes. Resources follow plan(settings, camera, inputs); when the size or
  // the plan changes only the images that changed are reallocated, and a failure keeps the
  // previous configuration. Errors (bad settings or camera,
  // texture 0, an unsupported or mismatched internal format, an input not the viewport plus twice
  // the guard band or, with Inputs::region, too small to hold it there, an input also passed as output, shader or
  // driver failures) return a Status naming the problem and leave the GL state unchanged.
  Status render(const Camera& camera, const Settings& settings, const Inputs& inputs,
                const RenderOptions& options = {});

  // The texture holding the result of the last successful render(): the caller's output or the
  // effect-owned GL_R16F texture (valid until the next render or the effect's destruction).
  std::uint32_t aoTexture() const;
  // Counts the changes of the effect-owned output texture object: it goes up whenever render()
  // creates a new one (first render, a resize, a changed plan) or deletes it (an Inputs::output
  // given instead). Anything that holds aoTexture()'s name (a descriptor, a bound unit, an FBO
  // attachment) must be refreshed when it differs from the value seen last (GL reuses names, so
  // comparing names cannot tell). Starts at 0; the caller's own output never changes it.
  std::uint64_t outputGeneration() const;
  // The GL texture serving a resource in the last render (intermediates for debugging and tests:
  // csz is GL_R32F with plan().cszLevels levels, ao_raw and ao_low GL_RG32F, or GL_RG16F with half_intermediates); 0 if not planned.
  std::uint32_t texture(gen::ResourceId resource) const;
  const Plan& plan() const;           // the plan of the last successful render()
  const ParamBlock& params() const;   // the parameter block it used
  const Timings& timings() const;     // method None unless the last render measured time
  const Stats& stats() const;

 private:
  struct Impl;
  SAO_GL_LOCAL explicit Effect(std::unique_ptr<Impl> impl);
  SAO_GL_LOCAL static Status createImpl(GetProcAddressFn getProcAddress, std::unique_ptr<Effect>& out, int headerVersion);
  std::unique_ptr<Impl> impl_;
};

}  // namespace sao::SAO_GL_API_NS
