// sao::gl — the OpenGL 4.3 backend: runs the generated GLSL 4.30 compute passes of the effect in
// the caller's current GL context.
//
//   std::unique_ptr<sao::gl::Effect> effect;
//   sao::Status st = sao::gl::Effect::create(glfwGetProcAddress, effect);  // or eglGetProcAddress, ...
//   ...
//   st = effect->render(camera, settings, {.depth = {depthTex, GL_DEPTH_COMPONENT24}});
//   GLuint ao = effect->aoTexture();   // GL_R16F, viewport size, linear visibility A in [0, 1]
//   // or your own GL_R8 / GL_R16F / GL_RGBA8 / GL_RGBA16F texture: Inputs::output, ::outputChannels
//
// Contract:
//  - Every call (create, render, the destructor) needs the context the effect was created in to be
//    current on the calling thread (timer queries are not shared between contexts). The library
//    has no global GL symbols: it calls only entry points loaded through the getProcAddress given
//    to create(). Errors come back as a Status; the library never calls glGetError (which would
//    take the caller's pending errors away).
//  - render() leaves the GL state as it found it: program, active texture unit, the 2D texture
//    and sampler bindings of the units it uses, the image units it uses, the uniform-buffer
//    bindings (generic and index 0), the query-buffer binding, and the parameters it sets on the
//    caller's textures (base level, depth-stencil texture mode, red swizzle). It does not touch
//    framebuffers, the viewport, pixel-store state, vertex state or capabilities.
//  - The caller's texture parameters (compare mode, base/max level, depth-stencil texture mode,
//    filters) do not change the result: the depth is read through the effect's own sampler
//    (GL_NEAREST, compare mode GL_NONE) at level 0.
//  - Synchronisation: render() issues glMemoryBarrier(texture fetch | image access) before its
//    first pass (so depth written by the caller's own image stores is visible) and, after its
//    last pass, the barriers needed to read the result by texture fetch, image load, framebuffer
//    read, glGetTexImage or a copy. Depth written by rendering needs no barrier. Between its
//    passes it issues only the barrier bits the schedule's hazards need (sao/schedule.h).
//  - Allocation: a render() with the same settings and kinds of input as the previous successful
//    one, and a camera that plans like its camera (sao::cameraKeepsPlan), allocates nothing (host
//    or GL storage; Inputs::layer's views are names without storage); anything else plans again.
//  - Textures are GL_TEXTURE_2D (or a layer of a GL_TEXTURE_2D_ARRAY: Inputs::layer); level 0 is
//    read and written. The depth input may also be a
//    GL_TEXTURE_2D_MULTISAMPLE (GL 4.5 or ARB_direct_state_access): it is read directly, one
//    sample per texel as Camera::depthSamplePolicy says (sample 0, or the one nearest to the
//    camera), with no resolve pass. Every other texture multisampled is refused (UnsupportedFormat),
//    and so is a multisampled depth with a second layer.
#pragma once
#include "sao/gl/effect_common.h"

#define SAO_GL_API_NS gl
#include "sao/gl/effect_api.inl"
#undef SAO_GL_API_NS
