#include "inputs.h"

#include <algorithm>
#include <string>

#include "sao/inputs.h"

namespace sao::SAO_GL_NS::detail {
namespace {

// What a texture is inspected for: its role in messages, whether it may be multisampled (an input
// a select=multisampled: variant reads, the depth; every other texture is single-sample), and the
// layer of an array texture to view (Inputs::layer).
struct Request {
  std::string_view role;
  bool multisampleAllowed;
  std::uint32_t layer;
  LayerViews& views;
};

bool isArray(GLenum target) { return target == GL_TEXTURE_2D_ARRAY || target == GL_TEXTURE_2D_MULTISAMPLE_ARRAY; }

Status inspect(const GlFunctions& gl, GLuint unit, GLuint texture, const Request& rq, TextureInfo& out) {
  // Built only for an error: render() allocates nothing per frame.
  auto who = [&] { return std::string(kApiName) + ": the " + std::string(rq.role) + " texture " + std::to_string(texture); };
  if (texture == 0)
    return Status::error(StatusCode::InvalidInput, std::string(kApiName) + ": the " + std::string(rq.role) + " texture is 0");
  if (!gl.IsTexture(texture))
    return Status::error(StatusCode::InvalidInput, who() + " is not a texture object (never bound, or deleted)");
  GLenum target = GL_TEXTURE_2D;
  if (gl.hasDsa) {
    GLint t = 0;
    gl.GetTextureParameteriv(texture, GL_TEXTURE_TARGET, &t);
    target = GLenum(t);
    const bool multisampled = target == GL_TEXTURE_2D_MULTISAMPLE || target == GL_TEXTURE_2D_MULTISAMPLE_ARRAY;
    if (multisampled && !rq.multisampleAllowed)
      return Status::error(StatusCode::UnsupportedFormat,
                           who() + " is multisampled (" + glEnumName(target) +
                               "); only the depth input may be a GL_TEXTURE_2D_MULTISAMPLE (read per "
                               "Camera::depthSamplePolicy); this texture must be a single-sample GL_TEXTURE_2D");
    if (target != GL_TEXTURE_2D && target != GL_TEXTURE_2D_MULTISAMPLE && !isArray(target))
      return Status::error(StatusCode::InvalidInput, who() + " is a " + glEnumName(target) +
                                                         "; the effect reads and writes GL_TEXTURE_2D level 0 (or "
                                                         "one layer of a GL_TEXTURE_2D_ARRAY: Inputs::layer)");
    if (!isArray(target) && rq.layer != 0)
      return Status::error(StatusCode::InvalidInput,
                           who() + " is a " + glEnumName(target) + ", which has no layers, but Inputs::layer is " +
                               std::to_string(rq.layer) +
                               " (stereo: give every texture as a GL_TEXTURE_2D_ARRAY, or layer 0)");
  } else if (rq.layer != 0) {
    return Status::error(StatusCode::InvalidInput, std::string(kApiName) + ": Inputs::layer is " + std::to_string(rq.layer) +
                                                       (kEs ? ", but OpenGL ES reads no array textures here (no way to "
                                                              "query a texture's target)"
                                                            : ", but array textures need GL 4.5 or ARB_direct_state_access"));
  }
  // Without DSA (GL 4.3 / 4.4) the target cannot be queried without binding: a texture of another
  // target (multisampled, array, 3D, ...) fails to bind (a GL error the caller's debug output
  // shows) and leaves the binding unchanged, which is checked below. The unit is cleared first so
  // that a failed bind cannot leave the caller's own texture there to be inspected instead.
  GLenum binding = GL_TEXTURE_BINDING_2D;
  switch (target) {
    case GL_TEXTURE_2D_MULTISAMPLE: binding = GL_TEXTURE_BINDING_2D_MULTISAMPLE; break;
    case GL_TEXTURE_2D_ARRAY: binding = GL_TEXTURE_BINDING_2D_ARRAY; break;
    case GL_TEXTURE_2D_MULTISAMPLE_ARRAY: binding = GL_TEXTURE_BINDING_2D_MULTISAMPLE_ARRAY; break;
    default: break;
  }
  gl.ActiveTexture(GL_TEXTURE0 + unit);
  gl.BindTexture(target, 0);
  gl.BindTexture(target, texture);
  GLint bound = 0;
  gl.GetIntegerv(binding, &bound);
  if (GLuint(bound) != texture)
    return Status::error(StatusCode::InvalidInput,
                         who() + " cannot be bound as GL_TEXTURE_2D (multisampled, an array, 3D or a cube map?); the "
                               "effect reads and writes GL_TEXTURE_2D level 0" +
                             (kEs ? std::string(" (on OpenGL ES every input is a single-sample GL_TEXTURE_2D)")
                                  : std::string(" (a multisampled depth input needs GL 4.5 or ARB_direct_state_access, "
                                                "to be recognised without a failing bind)")));
  GLint format = 0, w = 0, h = 0, layers = 1, stencil = 0, samples = 0, immutable = 0;
  gl.GetTexLevelParameteriv(target, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
  gl.GetTexLevelParameteriv(target, 0, GL_TEXTURE_WIDTH, &w);
  gl.GetTexLevelParameteriv(target, 0, GL_TEXTURE_HEIGHT, &h);
  gl.GetTexLevelParameteriv(target, 0, GL_TEXTURE_STENCIL_SIZE, &stencil);
  const bool multisampled = target == GL_TEXTURE_2D_MULTISAMPLE || target == GL_TEXTURE_2D_MULTISAMPLE_ARRAY;
  if (multisampled) gl.GetTexLevelParameteriv(target, 0, GL_TEXTURE_SAMPLES, &samples);
  if (isArray(target)) {
    gl.GetTexLevelParameteriv(target, 0, GL_TEXTURE_DEPTH, &layers);
    gl.GetTexParameteriv(target, GL_TEXTURE_IMMUTABLE_FORMAT, &immutable);
  }
  gl.BindTexture(target, 0);
  if (w <= 0 || h <= 0) return Status::error(StatusCode::InvalidInput, who() + " has no level 0 image");
  GLuint read = texture;
  if (isArray(target)) {
    // One layer through a texture view: the passes then read and write a GL_TEXTURE_2D(_MULTISAMPLE).
    if (!immutable)
      return Status::error(StatusCode::InvalidInput,
                           who() + " is a " + glEnumName(target) +
                               " without immutable storage (glTexImage3D); the effect reads one layer through a "
                               "texture view, which needs glTexStorage3D");
    if (rq.layer >= std::uint32_t(layers))
      return Status::error(StatusCode::InvalidInput, who() + " has " + std::to_string(layers) +
                                                         " layers, but Inputs::layer is " + std::to_string(rq.layer));
    target = multisampled ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
    read = rq.views.make(texture, target, GLenum(format), rq.layer);
    if (read == 0)
      return Status::error(StatusCode::DriverError, who() + ": glTextureView of layer " + std::to_string(rq.layer) +
                                                        " failed");
  }
  out.target = target;
  out.samples = multisampled ? std::uint32_t(std::max(samples, 1)) : 1u;
  out.texture = read;
  out.internalFormat = GLenum(format);
  out.hasStencil = stencil > 0;
  out.extent = {std::uint32_t(w), std::uint32_t(h)};
  return Status::success();
}

// The effect's format of a GL output texture; Depth (never an output format) for any other.
gen::Format outputFormat(GLenum f) {
  if constexpr (kEs) {
    // The output format whose GLES form the texture has (the effect's `target gles` rule: GL_R32F
    // stands for r16f); none for a format the effect refuses on ES.
    for (std::size_t i = 0; i < gen::kFormatInfo.size(); ++i) {
      const auto format = gen::Format(i);
      if (isOutputFormat(format) && !gen::glesRefuses(format) &&
          gen::formatInfo(gen::glesStorageFormat(format)).glInternalFormat == f)
        return format;
    }
    return gen::Format::Depth;
  }
  switch (f) {
    case GL_R16F: return gen::Format::R16F;
    case GL_R8: return gen::Format::R8;
    case GL_RGBA8: return gen::Format::RGBA8;
    case GL_RGBA16F: return gen::Format::RGBA16F;
    default: return gen::Format::Depth;
  }
}

bool isHardwareDepth(GLenum f) {
  switch (f) {
    case GL_DEPTH_COMPONENT16:
    case GL_DEPTH_COMPONENT24:
    case GL_DEPTH_COMPONENT32F:
    case GL_DEPTH24_STENCIL8:
    case GL_DEPTH32F_STENCIL8:
    case GL_DEPTH_COMPONENT:  // unsized (glTexImage2D with GL_DEPTH_COMPONENT)
    case GL_DEPTH_STENCIL: return true;
    default: return false;
  }
}

// The channels of a colour texture the effect reads as float (texelFetch of a sampler2D); 0 for
// any other format.
std::uint32_t colourChannels(GLenum f) {
  switch (f) {
    case GL_RGBA16F:
    case GL_RGBA32F:
    case GL_RGBA8_SNORM:
    case GL_RGBA16_SNORM: return 4;
    case GL_RGB16F:
    case GL_RGB32F: return 3;
    case GL_RG16F:
    case GL_RG32F:
    case GL_RG8_SNORM:
    case GL_RG16_SNORM: return 2;
    case GL_R16F:
    case GL_R32F:
    case GL_R8_SNORM:
    case GL_R16_SNORM: return 1;
    default: return 0;
  }
}

std::string glFormatName(gen::Format f) { return glEnumName(gen::formatInfo(f).glInternalFormat); }

// The texture of input `id` against the effect's contract (sao/inputs.h): a depth input's format
// and encoding (every depth input holds the first one's), a colour input's format and channels.
Status checkFormat(gen::ResourceId id, const TextureInfo& t, const Camera& camera, std::optional<DepthEncoding>& depth) {
  const std::string_view name = gen::kResources[static_cast<std::size_t>(id)].name;
  auto who = [&] { return std::string(kApiName) + ": the " + std::string(name) + " texture " + std::to_string(t.texture); };
  const GLenum f = t.internalFormat;
  if (!isDepthInput(id)) {
    const std::optional<gen::Format> format = formatOfGl(f);
    if (!colourInputRefused(id, format, colourChannels(f), camera)) return Status::success();
    return checkColourInput(id, format, colourChannels(f), camera, who(), glEnumName(f), glFormatName, "texture");
  }
  if (!isHardwareDepth(f) && f != GL_R32F)
    return Status::error(StatusCode::UnsupportedFormat,
                         who() + " is " + glEnumName(f) +
                             "; depth must be GL_DEPTH_COMPONENT16/24/32F, GL_DEPTH24_STENCIL8, "
                             "GL_DEPTH32F_STENCIL8 or GL_R32F (linear camera-space z)");
  const DepthEncoding encoding = f == GL_R32F ? DepthEncoding::LinearZ : DepthEncoding::Hardware;
  if (depth && *depth != encoding)
    return Status::error(StatusCode::InvalidInput,
                         who() + " is " + glEnumName(f) + " but the depth texture is " +
                             (*depth == DepthEncoding::LinearZ ? "GL_R32F" : "hardware depth") +
                             "; both must be hardware depth or both linear z");
  depth = encoding;
  return Status::success();
}

}  // namespace

Status checkInputs(const GlFunctions& gl, GLuint unit, const Inputs& inputs, const Camera& camera,
                   CheckedInputs& out) {
  out.region = inputs.region;
  std::optional<DepthEncoding> encoding;
  for (const gen::ResourceId id : gen::kInputIds) {
    const InputTexture& in = inputs[id];
    if (in.texture == 0 && !isRequiredInput(id)) continue;
    const std::string_view name = gen::kResources[static_cast<std::size_t>(id)].name;
    TextureInfo& t = out.inputs[id];
    if (Status st = inspect(gl, unit, in.texture, {name, mayBeMultisampled(id), inputs.layer, out.views}, t); !st)
      return st;
    if (in.internalFormat != 0 && in.internalFormat != t.internalFormat)
      return Status::error(StatusCode::InvalidInput, std::string(kApiName) + ": the " + std::string(name) + " texture " +
                                                         std::to_string(in.texture) + " was declared " +
                                                         glEnumName(in.internalFormat) + " but its level 0 is " +
                                                         glEnumName(t.internalFormat));
    if (Status st = checkFormat(id, t, camera, encoding); !st) return st;
    out.planInputs.supplied[id] = true;
  }
  out.planInputs.depthEncoding = encoding.value_or(DepthEncoding::Hardware);
  out.planInputs.depthSamples = out.inputs.depth.samples;
  if (inputs.output != 0) {
    const GLuint o = inputs.output;
    for (const gen::ResourceId id : gen::kInputIds)
      if (inputs[id].texture == o)
        return Status::error(StatusCode::InvalidInput,
                             std::string(kApiName) + ": texture " + std::to_string(o) + " is passed both as the output and as the " +
                                 std::string(gen::kResources[static_cast<std::size_t>(id)].name) +
                                 " input; the output must be a separate texture");
    if (Status st = inspect(gl, unit, o, {"output", false, inputs.layer, out.views}, out.output); !st) return st;
    const gen::Format format = outputFormat(out.output.internalFormat);
    if (!isOutputFormat(format))
      return Status::error(StatusCode::UnsupportedFormat,
                           std::string(kApiName) + ": the output texture " + std::to_string(o) + " is " +
                               glEnumName(out.output.internalFormat) +
                               (kEs ? "; on OpenGL ES 3.1 the effect writes GL_R32F, GL_RGBA8 or GL_RGBA16F (ES stores no "
                                      "r16f or r8 image: the effect's `target gles` rule)"
                                    : "; the effect writes GL_R16F, GL_R8, GL_RGBA8 or GL_RGBA16F"));
    out.planInputs.userOutput = true;
    out.planInputs.outputFormat = format;
  }
  return Status::success();
}

GLuint LayerViews::make(GLuint texture, GLenum viewTarget, GLenum internalFormat, GLuint layer) {
  if (count_ == views_.size()) return 0;
  GLuint view = 0;
  gl_.GenTextures(1, &view);
  if (view == 0) return 0;
  views_[count_++] = view;
  gl_.TextureView(view, viewTarget, texture, internalFormat, 0, 1, layer, 1);
  return gl_.IsTexture(view) ? view : 0;  // a failed glTextureView leaves the name without an object
}

SuppliedImages supplied(const CheckedInputs& in) {
  SuppliedImages images{};
  for (const gen::ResourceId id : gen::kInputIds)
    images[static_cast<std::size_t>(id)] = {in.inputs[id].texture != 0, in.inputs[id].extent, in.region};
  images[static_cast<std::size_t>(gen::ResourceId::ao)] = {in.output.texture != 0, in.output.extent, std::nullopt};
  return images;
}

}  // namespace sao::SAO_GL_NS::detail
