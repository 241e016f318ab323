// sao::gles — the OpenGL ES 3.1 backend: the OpenGL backend's code and API (sao/gl/effect.h, in
// namespace sao::gles) on an ES 3.1 or newer context, running the generated GLSL ES 3.10.
//
//   std::unique_ptr<sao::gles::Effect> effect;
//   sao::Status st = sao::gles::Effect::create(eglGetProcAddress, effect);
//   st = effect->render(camera, settings, {.depth = {depthTex, GL_DEPTH_COMPONENT24}});
//   GLuint ao = effect->aoTexture();   // GL_R32F on ES (below), viewport size, A in [0, 1]
//
// Where it differs from sao::gl (everything else, the state it restores included, is the same):
//  - ES 3.1 stores no r16f, rg16f, rg32f or r8 images. The effect declares what its images take
//    instead (`#pragma sao target gles` in effect/sao.glsl): the owned output is GL_R32F (holding the same binary16-rounded A as GL's GL_R16F),
//    the (A, key) intermediates GL_RGBA16F or GL_RGBA32F, width_run GL_RGBA16F and csz_share GL_RGBA32F. Your own output may be
//    GL_R32F (it takes r16f's place: one channel), GL_RGBA8 or GL_RGBA16F; GL_R16F and GL_R8 are
//    refused (UnsupportedFormat naming the rule). An RGBA output whose texels the final pass keeps
//    (Inputs::outputChannels, OutputBlend::Multiply) is read through a texture of itself, since ES
//    loads only r32f images back; the effect binds it on a texture unit of its own and restores it.
//  - Inputs are GL_TEXTURE_2Ds: ES cannot query a texture's target, so a multisampled depth and
//    Inputs::layer (array textures) are refused, as on GL 4.3 without direct state access.
//  - RenderOptions::measureTime uses GL_TIME_ELAPSED queries with EXT_disjoint_timer_query, else
//    glFinish and the CPU clock (Timings::method says which).
//  - The context needs GL_MAX_COMPUTE_IMAGE_UNIFORMS >= 8 (ES guarantees 4; linear_z writes the
//    eight csz levels at once): create() refuses a smaller one naming the limit.
#pragma once
#include "sao/gl/effect_common.h"

#define SAO_GL_API_NS gles
#include "sao/gl/effect_api.inl"
#undef SAO_GL_API_NS
