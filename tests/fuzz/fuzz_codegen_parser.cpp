// Fuzz target: the annotated-source front end of sao-shaderc: the loader (includes, #version and
// #extension lines), the directive parser (settings, constants, variants, exclusions, resources,
// the std140 block, passes) and, for a source that parses, the pass-variant expansion and the
// shader composition for both targets. glslang and SPIRV-Tools (third-party compilers) are not run.
//
// The input is written as entry.glsl in a scratch folder whose include/ holds the effect's and the
// mini effect's include files and inc/ the malformed corpus's, so that the seeds (effect/sao.glsl,
// tests/codegen/mini/mini.glsl, tests/codegen/malformed/*.glsl) load as they do in the tree.
// Invariants: no crash, no exception, no sanitizer report, no hang; every diagnostic has a message
// and a file; a source without errors yields passes, a block and composable shaders.
#include <cstdint>
#include <filesystem>
#include <string>

#include "diagnostics.h"
#include "directive_parser.h"
#include "fuzz_support.h"
#include "pass_builder.h"
#include "source_loader.h"

namespace {

namespace fs = std::filesystem;
using namespace sao::codegen;

void copyGlsl(const fs::path& from, const fs::path& to) {
  fs::create_directories(to);
  for (const auto& e : fs::directory_iterator(from))
    if (e.is_regular_file() && e.path().extension() == ".glsl")
      fs::copy_file(e.path(), to / e.path().filename(), fs::copy_options::overwrite_existing);
}

const fs::path& workDir() {
  static const fs::path* dir = [] {
    auto* d = new fs::path(sao::fuzz::scratchDir() / "codegen");
    copyGlsl(SAO_FUZZ_EFFECT_INCLUDE_DIR, *d / "include");
    copyGlsl(SAO_FUZZ_MINI_INCLUDE_DIR, *d / "include");
    copyGlsl(SAO_FUZZ_MALFORMED_INC_DIR, *d / "inc");
    return d;
  }();
  return *dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const fs::path entry = workDir() / "entry.glsl";
  sao::fuzz::writeFile(entry, data, size);
  Diagnostics diags;
  const LoadedSource source = loadSource(entry.string(), diags);
  Effect effect;
  if (!diags.hasErrors()) effect = parseEffect(source, diags);
  for (const Diagnostic& d : diags.all()) {
    SAO_FUZZ_CHECK(!d.message.empty() && !d.loc.file.empty(), "diagnostic: %s", d.format().c_str());
    SAO_FUZZ_CHECK(d.loc.line >= 0);
  }
  if (diags.hasErrors()) return 0;
  SAO_FUZZ_CHECK(!effect.passes.empty() && effect.block.has_value(), "a source without errors has passes and a block");
  for (const PassVariant& pv : buildPassVariants(effect)) {
    SAO_FUZZ_CHECK(pv.pass >= 0 && std::size_t(pv.pass) < effect.passes.size());
    SAO_FUZZ_CHECK(!composeShader(effect, pv, Target::OpenGL).empty());
    SAO_FUZZ_CHECK(!composeShader(effect, pv, Target::Vulkan).empty());
  }
  return 0;
}
