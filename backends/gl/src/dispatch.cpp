#include "dispatch.h"

#include <algorithm>

namespace sao::gl::detail {

GLuint textureFor(const PassResources& r, gen::ResourceId id) {
  switch (id) {
    case gen::ResourceId::depth: return r.inputs->depth.texture;
    case gen::ResourceId::depth2: return r.inputs->depth2.texture;
    case gen::ResourceId::normals: return r.inputs->normals.texture;
    default: break;
  }
  const auto& info = gen::kResources[static_cast<std::size_t>(id)];
  if (info.kind == gen::ResourceKind::Output && r.inputs->output.texture != 0) return r.inputs->output.texture;
  return r.owned->texture(id);
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

GLuint divUp(std::uint32_t n, std::uint32_t d) { return GLuint((n + d - 1) / d); }

Extent levelExtent(Extent e, std::uint32_t level) {
  return {std::max(1u, e.width >> level), std::max(1u, e.height >> level)};
}

// Level-0 extent of the image serving `id`.
Extent extentOf(const Plan& plan, gen::ResourceId id) {
  if (const PlannedImage* img = plan.image(id)) return img->extent;
  const auto& info = gen::kResources[static_cast<std::size_t>(id)];
  return info.inputExtent ? plan.inputExtent : plan.aoExtent;
}

}  // namespace

void dispatchPasses(const GlFunctions& gl, const Plan& plan, const std::vector<GLuint>& programs,
                    const PassResources& r, PassTimer& timer) {
  constexpr GLbitfield kBetweenPasses = GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT;
  for (std::size_t i = 0; i < plan.passes.size(); ++i) {
    const PlannedPass& p = plan.passes[i];
    const gen::PassInfo& info = gen::pass(p.pass);
    timer.beginPass(info.name);
    gl.UseProgram(programs[i]);
    for (std::uint32_t d = 0; d < p.dispatchCount; ++d) {
      const std::uint32_t level = info.perMip ? d + 1 : 0;  // level written
      Extent size{};
      bool haveSize = false;
      for (const gen::BindingInfo& b : p.variant->bindings) {
        const gen::ResourceId id = plan.resolve(p, b.resource);
        if (b.write) {
          const GLenum format = glFormat(gen::kResources[static_cast<std::size_t>(id)].format);
          gl.BindImageTexture(b.binding, textureFor(r, id), GLint(level), GL_FALSE, 0, GL_WRITE_ONLY, format);
          if (!haveSize) {
            size = levelExtent(extentOf(plan, id), level);
            haveSize = true;
          }
        } else {
          GLuint tex = textureFor(r, id);
          GLuint sampler = r.nearestSampler;
          if (info.perMip) {
            tex = r.owned->levelView(id, level - 1);  // level m-1 alone, read at lod 0
          } else if (const PlannedImage* img = plan.image(id); img && img->mipLevels > 1) {
            sampler = r.mipSampler;
          }
          gl.ActiveTexture(GL_TEXTURE0 + b.binding);
          gl.BindTexture(GL_TEXTURE_2D, tex);
          gl.BindSampler(b.binding, sampler);
        }
      }
      gl.DispatchCompute(divUp(size.width, info.localX), divUp(size.height, info.localY), 1);
      gl.MemoryBarrier(kBetweenPasses);
    }
    timer.endPass();
  }
}

}  // namespace sao::gl::detail
