// viewer_check: asserts on a sao-viewer screenshot. The image must not be blank (standard deviation
// of the luminance above a threshold) and, with --darker, one region must be darker than another
// by a margin (the AO view's crease or contact shadow against open floor).
//
//   viewer_check IMAGE.png [--min-stddev S] [--darker X0,Y0,X1,Y1 X0,Y0,X1,Y1 MARGIN]
//
// Regions are fractions of the image size (0,0 = top left). Luminance is in [0, 1].
// Exit status 0 when every check holds, 1 when one fails, 2 for bad arguments or unreadable files.
#include <stb/stb_image.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

struct Region {
  double x0, y0, x1, y1;
};

struct Image {
  int width = 0, height = 0;
  unsigned char* pixels = nullptr;  // RGB
  double luminance(int x, int y) const {
    const unsigned char* p = pixels + (std::size_t(y) * width + x) * 3;
    return (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / 255.0;
  }
};

[[noreturn]] void usage(const std::string& message) {
  std::fprintf(stderr, "viewer_check: %s\nusage: viewer_check IMAGE.png [--min-stddev S] [--darker X0,Y0,X1,Y1 X0,Y0,X1,Y1 MARGIN]\n",
               message.c_str());
  std::exit(2);
}

Region parseRegion(const std::string& text) {
  Region r{};
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf,%lf", &r.x0, &r.y0, &r.x1, &r.y1) != 4 || !(r.x0 < r.x1) ||
      !(r.y0 < r.y1) || r.x0 < 0 || r.y0 < 0 || r.x1 > 1 || r.y1 > 1)
    usage("bad region '" + text + "' (X0,Y0,X1,Y1 in [0, 1], X0 < X1, Y0 < Y1)");
  return r;
}

double parseNumber(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end || !std::isfinite(v)) usage("bad number '" + text + "'");
  return v;
}

double mean(const Image& image, const Region& r) {
  const int x0 = int(r.x0 * image.width), x1 = std::max(x0 + 1, int(r.x1 * image.width));
  const int y0 = int(r.y0 * image.height), y1 = std::max(y0 + 1, int(r.y1 * image.height));
  double sum = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) sum += image.luminance(x, y);
  return sum / (double(x1 - x0) * (y1 - y0));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) usage("no image");
  double minStddev = 0.02;
  bool darker = false;
  Region dark{}, bright{};
  double margin = 0;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--min-stddev" && i + 1 < argc) minStddev = parseNumber(argv[++i]);
    else if (a == "--darker" && i + 3 < argc) {
      darker = true;
      dark = parseRegion(argv[++i]);
      bright = parseRegion(argv[++i]);
      margin = parseNumber(argv[++i]);
    } else usage("unknown or incomplete argument '" + a + "'");
  }
  Image image;
  int channels = 0;
  image.pixels = stbi_load(argv[1], &image.width, &image.height, &channels, 3);
  if (!image.pixels) usage(std::string("cannot read '") + argv[1] + "': " + stbi_failure_reason());

  double sum = 0, sum2 = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const double l = image.luminance(x, y);
      sum += l;
      sum2 += l * l;
    }
  const double n = double(image.width) * image.height;
  const double average = sum / n, stddev = std::sqrt(std::max(0.0, sum2 / n - average * average));
  bool ok = true;
  std::printf("%s: %dx%d, mean luminance %.4f, stddev %.4f (need > %.4f)\n", argv[1], image.width, image.height,
              average, stddev, minStddev);
  if (!(stddev > minStddev)) {
    std::printf("FAIL: the image is blank or nearly uniform\n");
    ok = false;
  }
  if (darker) {
    const double d = mean(image, dark), b = mean(image, bright);
    std::printf("darker region %.4f, brighter region %.4f: difference %.4f (need >= %.4f)\n", d, b, b - d, margin);
    if (!(b - d >= margin)) {
      std::printf("FAIL: the expected darkening is missing\n");
      ok = false;
    }
  }
  stbi_image_free(image.pixels);
  return ok ? 0 : 1;
}
