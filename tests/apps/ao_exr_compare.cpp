// ao_exr_compare A.exr B.exr MAX_STEPS [MAX_PIXELS_OVER [MAX_ABS]]: compares two EXRs of sao-render
// (ao.exr, or the 3-channel bent_normal.exr; binary16 values in float) value for value in binary16
// steps (the distance between their half-float bit patterns, ordered across the sign: -0 and +0 are
// 0 apart). A value is over when it is more than MAX_STEPS away and, with MAX_ABS, also more than
// MAX_ABS apart (a unit vector's component near 0 is the difference of larger terms: its rounding is
// absolute, not relative to it). Prints the largest distance, the value's pixel, the number of
// differing values and of those over; exits 0 when at most MAX_PIXELS_OVER (default 0) values are
// over, 1 otherwise, 2 on bad input (NaN, or images of other sizes or channel counts).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "sao/image.h"
#include "sao/io.h"

int main(int argc, char** argv) {
  if (argc < 4 || argc > 6) {
    std::fprintf(stderr, "usage: ao_exr_compare A.exr B.exr MAX_STEPS [MAX_PIXELS_OVER [MAX_ABS]]\n");
    return 2;
  }
  sao::FloatImage a, b;
  std::vector<std::string> na, nb;
  for (sao::Status s : {sao::readFloatExr(argv[1], a, na), sao::readFloatExr(argv[2], b, nb)})
    if (!s) {
      std::fprintf(stderr, "ao_exr_compare: %s\n", s.message.c_str());
      return 2;
    }
  if (a.extent != b.extent || a.channels != b.channels) {
    std::fprintf(stderr, "ao_exr_compare: %s and %s differ in size or in channels\n", argv[1], argv[2]);
    return 2;
  }
  auto ordered = [](float v) {  // binary16 patterns in the order of their values
    const long bits = long(sao::halfBits(v));
    return (bits & 0x8000) ? -(bits & 0x7FFF) : bits;
  };
  const long limit = std::strtol(argv[3], nullptr, 10);
  const long allowed = argc >= 5 ? std::strtol(argv[4], nullptr, 10) : 0;
  const double maxAbs = argc == 6 ? std::strtod(argv[5], nullptr) : -1.0;
  long worst = 0;
  std::size_t worstAt = 0, differing = 0, over = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i) {
    if (std::isnan(a.data[i]) || std::isnan(b.data[i])) {
      std::fprintf(stderr, "ao_exr_compare: value %zu is NaN\n", i);
      return 2;
    }
    const long d = std::labs(ordered(a.data[i]) - ordered(b.data[i]));
    differing += d != 0;
    over += d > limit && std::fabs(double(a.data[i]) - double(b.data[i])) > maxAbs;
    if (d > worst) worst = d, worstAt = i;
  }
  const std::size_t pixel = worstAt / a.channels;
  std::printf("max %ld binary16 steps (pixel %zu,%zu channel %zu: %.6g vs %.6g); %zu of %zu values differ, %zu by more "
              "than %ld%s (allowed %ld)\n",
              worst, pixel % a.extent.width, pixel / a.extent.width, worstAt % a.channels, a.data[worstAt],
              b.data[worstAt], differing, a.data.size(), over, limit, maxAbs >= 0 ? " and the absolute bound" : "", allowed);
  return long(over) <= allowed ? 0 : 1;
}
