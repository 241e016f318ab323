// ao_exr_compare A.exr B.exr MAX_STEPS [MAX_PIXELS_OVER]: compares two AO EXRs (sao-render's ao.exr,
// binary16 values in float) pixel for pixel in binary16 steps (the distance between their half-float
// bit patterns; AO is in [0, 1], where the patterns are ordered). Prints the largest distance, the
// pixel, the number of differing pixels and of those over MAX_STEPS; exits 0 when at most
// MAX_PIXELS_OVER (default 0) pixels are over MAX_STEPS, 1 otherwise, 2 on bad input.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "sao/image.h"
#include "sao/io.h"

int main(int argc, char** argv) {
  if (argc != 4 && argc != 5) {
    std::fprintf(stderr, "usage: ao_exr_compare A.exr B.exr MAX_STEPS [MAX_PIXELS_OVER]\n");
    return 2;
  }
  sao::FloatImage a, b;
  std::vector<std::string> na, nb;
  for (sao::Status s : {sao::readFloatExr(argv[1], a, na), sao::readFloatExr(argv[2], b, nb)})
    if (!s) {
      std::fprintf(stderr, "ao_exr_compare: %s\n", s.message.c_str());
      return 2;
    }
  if (a.extent != b.extent || a.channels != 1 || b.channels != 1) {
    std::fprintf(stderr, "ao_exr_compare: %s and %s differ in size or are not one channel\n", argv[1], argv[2]);
    return 2;
  }
  const long limit = std::strtol(argv[3], nullptr, 10);
  const long allowed = argc == 5 ? std::strtol(argv[4], nullptr, 10) : 0;
  long worst = 0;
  std::size_t worstAt = 0, differing = 0, over = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i) {
    if (!(a.data[i] >= 0 && b.data[i] >= 0)) {
      std::fprintf(stderr, "ao_exr_compare: pixel %zu is negative or NaN\n", i);
      return 2;
    }
    const long d = std::labs(long(sao::halfBits(a.data[i])) - long(sao::halfBits(b.data[i])));
    differing += d != 0;
    over += d > limit;
    if (d > worst) worst = d, worstAt = i;
  }
  std::printf("max %ld binary16 steps (pixel %zu,%zu: %.6g vs %.6g); %zu of %zu pixels differ, %zu by more than %ld "
              "(allowed %ld)\n",
              worst, worstAt % a.extent.width, worstAt / a.extent.width, a.data[worstAt], b.data[worstAt], differing,
              a.data.size(), over, limit, allowed);
  return long(over) <= allowed ? 0 : 1;
}
