// Heap allocations counted for the API's own library (tests/common/library_allocations.h): the
// harness's uploads and readbacks, in the test program, are not counted. For programs that link
// sao_test_allocations.
#pragma once
#include "harness.h"
#include "library_allocations.h"
#if __has_include(<sao/gl/effect.h>)
#include "sao/gl/effect.h"
#endif
#if __has_include(<sao/gles/effect.h>)
#include "sao/gles/effect.h"
#endif
#if __has_include(<sao/vulkan/effect.h>)
#include "sao/vulkan/effect.h"
#endif

namespace sao::exectest {

inline bool watchApiLibrary(Api api) {
#if __has_include(<sao/gl/effect.h>)
  if (api == Api::Gl) return test::watchLibraryOf(reinterpret_cast<const void*>(&gl::Effect::create));
#endif
#if __has_include(<sao/gles/effect.h>)
  if (api == Api::Gles) return test::watchLibraryOf(reinterpret_cast<const void*>(&gles::Effect::create));
#endif
#if __has_include(<sao/vulkan/effect.h>)
  if (api == Api::Vulkan) return test::watchLibraryOf(reinterpret_cast<const void*>(&vk::Effect::create));
#endif
  return false;
}

}  // namespace sao::exectest
