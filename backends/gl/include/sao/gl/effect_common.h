// What sao/gl/effect.h and sao/gles/effect.h share before their API: includes and export macros.
#pragma once
#include <cstdint>
#include <memory>

#include "sao/camera.h"
#include "sao/output.h"
#include "sao/plan.h"
#include "sao/presets.h"  // presetSettings(): what every integration starts from
#include "sao/settings.h"
#include "sao/status.h"
#include "sao/timing.h"
#include "sao/version.h"

#if defined(_WIN32)
#  if defined(SAO_GL_BUILDING)
#    define SAO_GL_API __declspec(dllexport)
#  else
#    define SAO_GL_API __declspec(dllimport)
#  endif
#  define SAO_GL_LOCAL
#else
#  define SAO_GL_API __attribute__((visibility("default")))
#  define SAO_GL_LOCAL __attribute__((visibility("hidden")))
#endif

