// viewer_check: asserts on a sao-viewer screenshot. The image must not be blank (standard deviation
// of the luminance above a threshold) and, with --darker, one region must be darker than another
// by a margin (the AO view's crease or contact shadow against open floor). --min-chroma asks for
// a colourful image (mean of max - min channel per pixel, the normals view) and --rgb for a
// region's mean colour within a tolerance per channel (repeatable). --same-as asks that a region
// equal another screenshot of the same size there, every channel of every pixel exactly, and
// --differs-from that at least N of a region's pixels differ from another's (the split-resolution
// view against the AO view at each divisor; both repeatable).
//
//   viewer_check IMAGE.png [--min-stddev S] [--darker X0,Y0,X1,Y1 X0,Y0,X1,Y1 MARGIN]
//                [--min-chroma C] [--rgb X0,Y0,X1,Y1 R,G,B TOLERANCE]...
//                [--same-as OTHER.png X0,Y0,X1,Y1]... [--differs-from OTHER.png X0,Y0,X1,Y1 N]...
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

// A region compared pixel by pixel with another screenshot: `minDiffering` 0 asks for equality.
struct PixelCheck {
  std::string other;
  Region region;
  long minDiffering = 0;
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
               " [--min-chroma C] [--rgb X0,Y0,X1,Y1 R,G,B TOLERANCE]... [--same-as OTHER.png X0,Y0,X1,Y1]..."
               " [--differs-from OTHER.png X0,Y0,X1,Y1 N]...\n",
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
// The pixel rectangle of a region, at least one pixel.
void bounds(const Image& image, const Region& r, int& x0, int& y0, int& x1, int& y1) {
  x0 = int(r.x0 * image.width), x1 = std::max(x0 + 1, int(r.x1 * image.width));
  y0 = int(r.y0 * image.height), y1 = std::max(y0 + 1, int(r.y1 * image.height));
}


template <class F>
double meanOver(const Image& image, const Region& r, F f) {
  int x0, y0, x1, y1;
  bounds(image, r, x0, y0, x1, y1);
  double sum = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) sum += f(x, y);
  return sum / (double(x1 - x0) * (y1 - y0));
}

double mean(const Image& image, const Region& r) {
  return meanOver(image, r, [&](int x, int y) { return image.luminance(x, y); });
}

// Pixels of the region whose RGB differ between the images (same size), and the largest
// channel difference among them (0..255).
long differing(const Image& a, const Image& b, const Region& r, int& maxDelta) {
  int x0, y0, x1, y1;
  bounds(a, r, x0, y0, x1, y1);
  long n = 0;
  maxDelta = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const unsigned char* p = a.pixels + (std::size_t(y) * a.width + x) * 3;
      const unsigned char* q = b.pixels + (std::size_t(y) * b.width + x) * 3;
      int d = 0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(p[c]) - int(q[c])));
      if (d > 0) ++n;
      maxDelta = std::max(maxDelta, d);
    }
  return n;
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
  std::vector<PixelCheck> pixelChecks;
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
    } else if (a == "--same-as" && i + 2 < argc) {
      const std::string other = argv[++i];
      pixelChecks.push_back({other, parseRegion(argv[++i]), 0});
    } else if (a == "--differs-from" && i + 3 < argc) {
      const std::string other = argv[++i];
      const Region region = parseRegion(argv[++i]);
      const double n = parseNumber(argv[++i]);
      if (!(n >= 1) || n != std::floor(n)) usage("bad pixel count '" + std::string(argv[i]) + "' (a whole number >= 1)");
      pixelChecks.push_back({other, region, long(n)});
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
  for (const auto& c : pixelChecks) {
    Image other;
    int otherChannels = 0;
    other.pixels = stbi_load(c.other.c_str(), &other.width, &other.height, &otherChannels, 3);
    if (!other.pixels) usage("cannot read '" + c.other + "': " + stbi_failure_reason());
    if (other.width != image.width || other.height != image.height)
      usage("'" + c.other + "' is " + std::to_string(other.width) + "x" + std::to_string(other.height) + ", not " +
            std::to_string(image.width) + "x" + std::to_string(image.height));
    int x0, y0, x1, y1, maxDelta = 0;
    bounds(image, c.region, x0, y0, x1, y1);
    const long n = differing(image, other, c.region, maxDelta);
    std::printf("pixels x %d..%d, y %d..%d against %s: %ld of %ld differ (largest channel difference %d); need %s\n",
                x0, x1 - 1, y0, y1 - 1, c.other.c_str(), n, long(x1 - x0) * (y1 - y0), maxDelta,
                c.minDiffering == 0 ? "none" : ("at least " + std::to_string(c.minDiffering)).c_str());
    if (c.minDiffering == 0 ? n != 0 : n < c.minDiffering) {
      std::printf(c.minDiffering == 0 ? "FAIL: the region is not the same as in %s\n"
                                      : "FAIL: the region is too close to %s to tell them apart\n",
                  c.other.c_str());
      ok = false;
    }
    stbi_image_free(other.pixels);
  }
  stbi_image_free(image.pixels);
  return ok ? 0 : 1;
}
