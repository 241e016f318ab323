// walkthrough_cpu_oracle OUT: the real effect's CPU reference (float precision, the GPU's
// arithmetic) on every walkthrough case; writes per case the depth it rendered and the final ao
// to OUT. It runs in its own process because it links the real effect's sao::core, and
// walkthrough_test links the extended one (the same symbols).
#include <cstdio>
#include <vector>

#include "oracle_file.h"
#include "sao/cpu/reference.h"
#include "walkthrough_case.h"

int main(int argc, char** argv) {
  using namespace sao;
  if (argc != 2) {
    std::fprintf(stderr, "usage: walkthrough_cpu_oracle OUT_FILE\n");
    return 2;
  }
  std::vector<walkthrough::Words> images;
  for (const walkthrough::Case& c : walkthrough::cases()) {
    const DepthImage depth = walkthrough::caseDepth();
    cpu::Inputs inputs;
    inputs.depth = &depth;
    cpu::Result result;
    const Status st = cpu::run(c.settings, walkthrough::caseCamera(), inputs, {cpu::Precision::Float, 2}, result);
    if (!st) {
      std::fprintf(stderr, "walkthrough_cpu_oracle: case %s: %s\n", c.name, st.message.c_str());
      return 1;
    }
    images.push_back(walkthrough::wordsOf(depth));
    images.push_back(walkthrough::wordsOf(result.ao));
  }
  if (!walkthrough::writeWords(argv[1], images)) {
    std::fprintf(stderr, "walkthrough_cpu_oracle: cannot write %s\n", argv[1]);
    return 1;
  }
  return 0;
}
