// Expands every pass into its compiled variants: the variant combinations a pass needs, its
// bindings, and the GLSL text for each target with a line map back to the annotated source.
#pragma once
#include <string>
#include <vector>

#include "effect_model.h"

namespace sao::codegen {

// OpenGLES: GL text for OpenGL ES 3.1, compiled to SPIR-V and written as GLSL ES 3.10 from it: each
// write's GLES storage format, and a load of a write that ES cannot read back through the image
// (every format but r32f) made through a texture of the same image (Binding::esKeptUnit).
enum class Target { OpenGL, Vulkan, OpenGLES };

struct Binding {
  int binding = 0;  // Vulkan set-0 binding (one numbering for reads and writes, 0 = the parameter block)
  int unit = 0;     // GL texture unit (a read) or image unit (a write): each counted from 0, so that
                    // a pass's image units stay within GL's minimum of 8
  int slots = 1;    // array elements: a levels= pass's write of a MIP chain, one per level
  int resource = 0;
  bool write = false;
  std::string format;      // the storage format of a write (per variant for a formats= output)
  bool readWrite = false;  // a write the pass may also imageLoad (a formats= output: kept channels, multiply)
  bool multisampled = false;  // a read of an input whose select=multisampled: variant is 1: sampler2DMS
  std::string esFormat;    // a write's storage format on GLES (target_rules.h); empty: none there
  int esKeptUnit = -1;     // GLES: a readWrite write's texels are loaded through this texture unit
};

struct PassVariant {
  int pass = 0;
  std::vector<int> values;  // one per effect variant; -1 where the pass does not depend on it
  std::vector<Binding> bindings;
  std::string stem;  // file name stem, e.g. "ao.NORMALS_SUPPLIED1.TWO_LAYER0"
  bool onGles = true;  // every write has a GLES storage format: the variant exists on GLES
};

// Every non-excluded combination of all variants, in mixed-radix order (first variant slowest).
std::vector<std::vector<int>> allowedCombinations(const Effect& effect);

// Each pass's distinct variant projections of the allowed combinations, in pass order.
std::vector<PassVariant> buildPassVariants(const Effect& effect);

// The compute shader text for one pass variant and target; line i came from lines[i].loc.
std::vector<SourceLine> composeShader(const Effect& effect, const PassVariant& pv, Target target);

std::string joinLines(const std::vector<SourceLine>& lines);

}  // namespace sao::codegen
