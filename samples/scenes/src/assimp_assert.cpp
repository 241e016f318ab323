// Debian's libassimp is built without NDEBUG, so its internal consistency checks (ai_assert) are
// live and end the process with abort() - reachable from malformed files (a PLY whose faces make
// the triangulation step's count disagree did it within the first seconds of fuzzing). That
// build does not export assimp's own setAiAssertHandler, but it does export the function every
// ai_assert calls, and calls it through the PLT: this definition takes its place for the whole
// program and throws instead. Importer::ReadFile catches the exception and fails the read; the
// mesh reader reports it as the file's error ("assimp: internal check failed: ...").
#include <assimp/ai_assert.h>

#include <string>

#include "assimp_assert.h"

namespace Assimp {

void aiAssertViolation(const char* failedExpression, const char* file, int line) {
  throw sao::scenes::detail::AssimpCheckFailed(std::string("internal check failed: ") +
                                               (failedExpression ? failedExpression : "?") + " (" +
                                               (file ? file : "?") + ":" + std::to_string(line) + ")");
}

}  // namespace Assimp

namespace sao::scenes::detail {

bool assimpAssertionsThrow() {
  try {
    Assimp::aiAssertViolation("self-test", __FILE__, __LINE__);
  } catch (const AssimpCheckFailed&) {
    return true;
  }
  return false;
}

}  // namespace sao::scenes::detail
