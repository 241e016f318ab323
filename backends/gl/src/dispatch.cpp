#include "dispatch.h"

namespace sao::gl::detail {

GLuint textureFor(const PassResources& r, gen::ResourceId id, bool previousFrame) {
  switch (id) {
    case gen::ResourceId::depth: return r.inputs->depth.texture;
    case gen::ResourceId::depth2: return r.inputs->depth2.texture;
    case gen::ResourceId::normals: return r.inputs->normals.texture;
    case gen::ResourceId::motion: return r.inputs->motion.texture;
    default: break;
  }
  const auto& info = gen::kResources[static_cast<std::size_t>(id)];
  if (info.kind == gen::ResourceKind::Output && r.inputs->output.texture != 0) return r.inputs->output.texture;
  return r.owned->texture(id, imageCopy(r.historyParity, id, previousFrame));
}

GLbitfield barrierBits(std::span<const Hazard> hazards) {
  GLbitfield bits = 0;
  for (const Hazard& h : hazards) switch (h.kind) {
      // Texel fetches after the barrier see the image stores before it.
      case HazardKind::ReadAfterWrite: bits |= GL_TEXTURE_FETCH_BARRIER_BIT; break;
      // Image stores after the barrier wait for every access before it.
      case HazardKind::WriteAfterRead:
      case HazardKind::WriteAfterWrite: bits |= GL_SHADER_IMAGE_ACCESS_BARRIER_BIT; break;
      // The caller's own shaders may have stored to an input.
      case HazardKind::CallerWrote: bits |= GL_TEXTURE_FETCH_BARRIER_BIT; break;
      // Whatever way the caller reads the result next.
      case HazardKind::CallerReads:
        bits |= GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                GL_FRAMEBUFFER_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT;
        break;
    }
  return bits;
}

Status preparePrograms(Programs& programs, const Plan& plan, std::vector<GLuint>& out, std::uint64_t& compiled) {
  out.assign(plan.passes.size(), 0);
  for (std::size_t i = 0; i < plan.passes.size(); ++i) {
    const PlannedPass& p = plan.passes[i];
    if (Status st = programs.get(gen::pass(p.pass), *p.variant, out[i], compiled); !st) return st;
  }
  return Status::success();
}

namespace {

void barrier(const GlFunctions& gl, std::span<const Hazard> hazards) {
  if (const GLbitfield bits = barrierBits(hazards)) gl.MemoryBarrier(bits);
}

// `declared`: the pass variant's own binding (the format its shader declares, whether it loads too).
void bind(const GlFunctions& gl, const PassResources& r, const ScheduledBinding& b, const gen::BindingInfo& declared) {
  const GLuint texture = textureFor(r, b.resource, b.previousFrame);
  if (b.write) {
    // A levels= write is an image array: unit + j holds level baseLevel + j, the last level past the chain.
    for (std::uint32_t slot = 0; slot < declared.slots; ++slot)
      gl.BindImageTexture(declared.glUnit + slot, texture, GLint(b.slotLevel(slot)),
                          GL_FALSE, 0, declared.readWrite ? GL_READ_WRITE : GL_WRITE_ONLY, glFormat(declared.format));
    return;
  }
  // A read sees the whole chain (lod chosen by the shader) or level 0 (create() refuses an effect
  // with a read of one level above 0 alone, which would need a view).
  const GLuint tex = texture;
  const GLuint sampler = b.wholeChain ? r.mipSampler : r.nearestSampler;
  gl.ActiveTexture(GL_TEXTURE0 + declared.glUnit);
  // The caller's depth may be multisampled (sampler2DMS in linear_z's DEPTH_MULTISAMPLE variant).
  const bool depth = b.resource == gen::ResourceId::depth;
  gl.BindTexture(depth ? r.inputs->depth.target : GLenum(GL_TEXTURE_2D), tex);
  gl.BindSampler(declared.glUnit, sampler);
}

}  // namespace

void runSchedule(const GlFunctions& gl, const Plan& plan, const Schedule& schedule, const std::vector<GLuint>& programs,
                 const PassResources& r, PassTimer& timer) {
  barrier(gl, schedule.entryHazards());
  const ScheduledDispatch* previous = nullptr;
  for (const ScheduledDispatch& d : schedule.dispatches) {
    const bool newPass = !previous || previous->passIndex != d.passIndex;
    if (newPass) {
      if (previous) timer.endPass();
      timer.beginPass(gen::pass(plan.passes[d.passIndex].pass).name);
      gl.UseProgram(programs[d.passIndex]);
    }
    barrier(gl, schedule.hazardsBefore(d));
    const std::span<const ScheduledBinding> bindings = schedule.bindingsOf(d);  // one to one with the variant's
    for (std::size_t i = 0; i < bindings.size(); ++i) bind(gl, r, bindings[i], d.variant->bindings[i]);
    gl.DispatchCompute(d.groupsX, d.groupsY, 1);
    previous = &d;
  }
  if (previous) timer.endPass();
  barrier(gl, schedule.exitHazards());
}

}  // namespace sao::gl::detail
