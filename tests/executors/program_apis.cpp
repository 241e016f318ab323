// The APIs one program of the shared suite runs: the library's (GL, Vulkan) as built into the
// harness, the engine-side example where the program is declared ENGINE and sao::gles where it is
// declared GLES. Compiled into each program rather than into the harness library, so that
// SAO_EXEC_PROGRAM_ENGINE and SAO_EXEC_PROGRAM_GLES are the program's.
#include "harness_apis.h"

namespace sao::exectest {

std::vector<Api> apis() {
  std::vector<Api> v = libraryApis();
#if SAO_EXEC_PROGRAM_ENGINE
  v.push_back(Api::Engine);
#endif
#if SAO_EXEC_PROGRAM_GLES
  v.push_back(Api::Gles);
#endif
  return v;
}

}  // namespace sao::exectest
