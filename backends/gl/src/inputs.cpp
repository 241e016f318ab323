#include "inputs.h"

#include <algorithm>
#include <string>

namespace sao::gl::detail {
namespace {

// What a texture is inspected for: its role in messages, whether it may be multisampled (the depth
// input, read as sampler2DMS by DEPTH_MULTISAMPLE; every other texture is single-sample), and the
// layer of an array texture to view (Inputs::layer).
struct Request {
  const char* role;
  bool multisampleAllowed;
  std::uint32_t layer;
  LayerViews& views;
};

bool isArray(GLenum target) { return target == GL_TEXTURE_2D_ARRAY || target == GL_TEXTURE_2D_MULTISAMPLE_ARRAY; }

Status inspect(const GlFunctions& gl, GLuint unit, GLuint texture, const Request& rq, TextureInfo& out) {
  // Built only for an error: render() allocates nothing per frame.
  auto who = [&] { return std::string("sao::gl: the ") + rq.role + " texture " + std::to_string(texture); };
  if (texture == 0)
    return Status::error(StatusCode::InvalidInput, std::string("sao::gl: the ") + rq.role + " texture is 0");
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
    return Status::error(StatusCode::InvalidInput, "sao::gl: Inputs::layer is " + std::to_string(rq.layer) +
                                                       ", but array textures need GL 4.5 or ARB_direct_state_access");
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
                               "effect reads and writes GL_TEXTURE_2D level 0 (a multisampled depth input needs GL 4.5 "
                               "or ARB_direct_state_access, to be recognised without a failing bind)");
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

// The channels of a normals format the effect reads; 0 for any other format.
std::uint32_t normalChannels(GLenum f) {
  switch (f) {
    case GL_RGBA16F:
    case GL_RGBA32F:
    case GL_RGBA8_SNORM:
    case GL_RGBA16_SNORM: return 4;
    case GL_RGB16F:
    case GL_RGB32F: return 3;
    case GL_RG16F:  // octahedral encodings only (checkNormalsChannels)
    case GL_RG32F:
    case GL_RG8_SNORM:
    case GL_RG16_SNORM: return 2;
    default: return 0;
  }
}

Status depthInput(const GlFunctions& gl, GLuint unit, const DepthInput& in, const Request& rq, TextureInfo& out,
                  DepthEncoding& encoding) {
  const char* role = rq.role;
  if (Status st = inspect(gl, unit, in.texture, rq, out); !st) return st;
  auto who = [&] { return std::string("sao::gl: the ") + role + " texture " + std::to_string(in.texture); };
  const GLenum f = out.internalFormat;
  if (!isHardwareDepth(f) && f != GL_R32F)
    return Status::error(StatusCode::UnsupportedFormat,
                         who() + " is " + glEnumName(f) +
                             "; depth must be GL_DEPTH_COMPONENT16/24/32F, GL_DEPTH24_STENCIL8, "
                             "GL_DEPTH32F_STENCIL8 or GL_R32F (linear camera-space z)");
  if (in.internalFormat != 0 && in.internalFormat != f)
    return Status::error(StatusCode::InvalidInput, who() + " was declared " + glEnumName(in.internalFormat) +
                                                       " but its level 0 is " + glEnumName(f));
  encoding = f == GL_R32F ? DepthEncoding::LinearZ : DepthEncoding::Hardware;
  return Status::success();
}

}  // namespace

Status checkInputs(const GlFunctions& gl, GLuint unit, const Inputs& inputs, NormalsEncoding normalsEncoding,
                   CheckedInputs& out) {
  out.region = inputs.region;
  DepthEncoding encoding{};
  const std::uint32_t layer = inputs.layer;
  if (Status st = depthInput(gl, unit, inputs.depth, {"depth", true, layer, out.views}, out.depth, encoding); !st)
    return st;
  out.planInputs.depthEncoding = encoding;
  out.planInputs.depthSamples = out.depth.samples;
  if (inputs.depth2.texture != 0) {
    DepthEncoding encoding2{};
    if (Status st = depthInput(gl, unit, inputs.depth2, {"second-layer depth", false, layer, out.views}, out.depth2,
                               encoding2);
        !st)
      return st;
    if (encoding2 != encoding)
      return Status::error(StatusCode::InvalidInput,
                           std::string("sao::gl: the second depth layer is ") + glEnumName(out.depth2.internalFormat) +
                               " but the first is " + glEnumName(out.depth.internalFormat) +
                               "; both must be hardware depth or both linear z");
    out.planInputs.secondLayer = true;
  }
  if (inputs.normals != 0) {
    if (Status st = inspect(gl, unit, inputs.normals, {"normals", false, layer, out.views}, out.normals); !st) return st;
    const std::uint32_t channels = normalChannels(out.normals.internalFormat);
    // Built only for an error, like inspect()'s: render() allocates nothing per frame.
    auto what = [&] {
      return "sao::gl: the normals texture " + std::to_string(inputs.normals) + " is " +
             glEnumName(out.normals.internalFormat);
    };
    if (channels == 0)
      return Status::error(StatusCode::UnsupportedFormat,
                           what() + "; normals must be GL_RGBA16F, GL_RGBA32F, GL_RGB16F, GL_RGB32F, GL_RGBA8_SNORM, "
                                    "GL_RGBA16_SNORM or (octahedral encodings only) GL_RG16F, GL_RG32F, GL_RG8_SNORM, "
                                    "GL_RG16_SNORM");
    if (channels < normalsChannelsRead(normalsEncoding))
      return checkNormalsChannels(normalsEncoding, channels, what(), "texture");
    out.planInputs.normals = true;
  }
  if (inputs.motion != 0) {
    if (Status st = inspect(gl, unit, inputs.motion, {"motion", false, layer, out.views}, out.motion); !st) return st;
    const GLenum f = out.motion.internalFormat;
    if (f != GL_RG16F && f != GL_RG32F && f != GL_RGBA16F && f != GL_RGBA32F)
      return Status::error(StatusCode::UnsupportedFormat, "sao::gl: the motion texture " + std::to_string(inputs.motion) +
                                                              " is " + glEnumName(f) +
                                                              "; motion vectors must be GL_RG16F, GL_RG32F, GL_RGBA16F "
                                                              "or GL_RGBA32F (.xy in pixels)");
    out.planInputs.motion = true;
  }
  if (inputs.output != 0) {
    const GLuint o = inputs.output;
    const char* clash = o == inputs.depth.texture    ? "depth"
                        : o == inputs.depth2.texture ? "second-layer depth"
                        : o == inputs.normals        ? "normals"
                        : o == inputs.motion         ? "motion"
                                                     : nullptr;
    if (clash)
      return Status::error(StatusCode::InvalidInput, "sao::gl: texture " + std::to_string(o) +
                                                         " is passed both as the output and as the " + clash +
                                                         " input; the output must be a separate texture");
    if (Status st = inspect(gl, unit, o, {"output", false, layer, out.views}, out.output); !st) return st;
    const gen::Format format = outputFormat(out.output.internalFormat);
    if (!isOutputFormat(format))
      return Status::error(StatusCode::UnsupportedFormat, "sao::gl: the output texture " + std::to_string(o) + " is " +
                                                              glEnumName(out.output.internalFormat) +
                                                              "; the effect writes GL_R16F, GL_R8, GL_RGBA8 or GL_RGBA16F");
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
  auto add = [&](gen::ResourceId id, const TextureInfo& t) {
    const bool input = gen::kResources[static_cast<std::size_t>(id)].kind == gen::ResourceKind::Input;
    images[static_cast<std::size_t>(id)] = {t.texture != 0, t.extent, input ? in.region : std::nullopt};
  };
  add(gen::ResourceId::depth, in.depth);
  add(gen::ResourceId::depth2, in.depth2);
  add(gen::ResourceId::normals, in.normals);
  add(gen::ResourceId::motion, in.motion);
  add(gen::ResourceId::ao, in.output);
  return images;
}

}  // namespace sao::gl::detail
