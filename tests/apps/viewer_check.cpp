// viewer_check: asserts on a sao-viewer screenshot. The image must not be blank (standard deviation
// of the luminance above a threshold) and, with --darker, one region must be darker than another
// by a margin (the AO view's crease or contact shadow against open floor). --min-chroma asks for
// a colourful image (mean of max - min channel per pixel, the normals view) and --rgb for a
// region's mean colour within a tolerance per channel (repeatable).
//
//   viewer_check IMAGE.png [--min-stddev S] [--darker X0,Y0,X1,Y1 X0,Y0,X1,Y1 MARGIN]
//                [--min-chroma C] [--rgb X0,Y0,X1,Y1 R,G,B TOLERANCE]...
//
// Regions are fractions of the image size (0,0 = top left). Luminance and colours are in [0, 1].
// Exit status 0 when every check holds, 1 when one fails, 2 for bad arguments or unreadable files.
#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

struct Region {
  double x0, y0, x1, y1;
};

struct Rgb {
  double r = 0, g = 0, b = 0;
};

struct ColourCheck {
  Region region;
  Rgb want;
  double tolerance;
};

struct Image {
  int width = 0, height = 0;
  unsigned char* pixels = nullptr;  // RGB
  double luminance(int x, int y) const {
    const unsigned char* p = pixels + (std::size_t(y) * width + x) * 3;
    return (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / 255.0;
  }
  double chroma(int x, int y) const {
    const unsigned char* p = pixels + (std::size_t(y) * width + x) * 3;
    return (std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]})) / 255.0;
  }
};

[[noreturn]] void usage(const std::string& message) {
  std::fprintf(stderr,
               "viewer_check: %s\nusage: viewer_check IMAGE.png [--min-stddev S] [--darker X0,Y0,X1,Y1 X0,Y0,X1,Y1 MARGIN]"
               " [--min-chroma C] [--rgb X0,Y0,X1,Y1 R,G,B TOLERANCE]...\n",
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

Rgb parseRgb(const std::string& text) {
  Rgb c;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf", &c.r, &c.g, &c.b) != 3) usage("bad colour '" + text + "' (R,G,B in [0, 1])");
  return c;
}

double parseNumber(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end || !std::isfinite(v)) usage("bad number '" + text + "'");
  return v;
}

// The mean of f(x, y) over a region's pixels (at least one).
template <class F>
double meanOver(const Image& image, const Region& r, F f) {
  const int x0 = int(r.x0 * image.width), x1 = std::max(x0 + 1, int(r.x1 * image.width));
  const int y0 = int(r.y0 * image.height), y1 = std::max(y0 + 1, int(r.y1 * image.height));
  double sum = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) sum += f(x, y);
  return sum / (double(x1 - x0) * (y1 - y0));
}

double mean(const Image& image, const Region& r) {
  return meanOver(image, r, [&](int x, int y) { return image.luminance(x, y); });
}

Rgb meanColour(const Image& image, const Region& r) {
  auto channel = [&](int c) {
    return meanOver(image, r, [&](int x, int y) { return image.pixels[(std::size_t(y) * image.width + x) * 3 + c] / 255.0; });
  };
  return {channel(0), channel(1), channel(2)};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) usage("no image");
  double minStddev = 0.02;
  bool darker = false;
  Region dark{}, bright{};
  double margin = 0, minChroma = -1;
  std::vector<ColourCheck> colours;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--min-stddev" && i + 1 < argc) minStddev = parseNumber(argv[++i]);
    else if (a == "--darker" && i + 3 < argc) {
      darker = true;
      dark = parseRegion(argv[++i]);
      bright = parseRegion(argv[++i]);
      margin = parseNumber(argv[++i]);
    } else if (a == "--min-chroma" && i + 1 < argc) minChroma = parseNumber(argv[++i]);
    else if (a == "--rgb" && i + 3 < argc) {
      const Region region = parseRegion(argv[++i]);
      const Rgb want = parseRgb(argv[++i]);
      colours.push_back({region, want, parseNumber(argv[++i])});
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
  if (minChroma >= 0) {
    const double chroma = meanOver(image, {0, 0, 1, 1}, [&](int x, int y) { return image.chroma(x, y); });
    std::printf("mean chroma %.4f (need > %.4f)\n", chroma, minChroma);
    if (!(chroma > minChroma)) {
      std::printf("FAIL: the image is grey, not colourful\n");
      ok = false;
    }
  }
  for (const auto& c : colours) {
    const Rgb m = meanColour(image, c.region);
    std::printf("region %.2f,%.2f,%.2f,%.2f: mean colour %.4f,%.4f,%.4f (want %.4f,%.4f,%.4f within %.4f)\n", c.region.x0,
                c.region.y0, c.region.x1, c.region.y1, m.r, m.g, m.b, c.want.r, c.want.g, c.want.b, c.tolerance);
    if (!(std::abs(m.r - c.want.r) <= c.tolerance && std::abs(m.g - c.want.g) <= c.tolerance &&
          std::abs(m.b - c.want.b) <= c.tolerance)) {
      std::printf("FAIL: the region's colour is off\n");
      ok = false;
    }
  }
  stbi_image_free(image.pixels);
  return ok ? 0 : 1;
}
