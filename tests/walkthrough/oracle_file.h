// The file walkthrough_cpu_oracle writes and walkthrough_test reads: images as raw 32-bit words
// (depth texels, or the bits of float texels), so nothing is rounded on the way.
#pragma once
#include <bit>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "sao/image.h"

namespace sao::walkthrough {

struct Words {
  std::uint32_t width = 0, height = 0, channels = 0;
  std::vector<std::uint32_t> data;
  bool operator==(const Words&) const = default;
};

inline Words wordsOf(const DepthImage& d) { return {d.extent.width, d.extent.height, 1, d.texels}; }

inline Words wordsOf(const FloatImage& f) {
  Words w{f.extent.width, f.extent.height, f.channels, {}};
  for (float v : f.data) w.data.push_back(std::bit_cast<std::uint32_t>(v));
  return w;
}

inline FloatImage floatImageOf(const Words& w) {
  FloatImage f(Extent{w.width, w.height}, w.channels);
  for (std::size_t i = 0; i < w.data.size() && i < f.data.size(); ++i) f.data[i] = std::bit_cast<float>(w.data[i]);
  return f;
}

inline constexpr std::uint32_t kMagic = 0x4B4C5757;  // "WWLK"

// Magic, count, then per image: width, height, channels, width * height * channels words.
inline bool writeWords(const std::string& path, const std::vector<Words>& images) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  auto put = [&](std::uint32_t v) { out.write(reinterpret_cast<const char*>(&v), sizeof v); };
  put(kMagic);
  put(std::uint32_t(images.size()));
  for (const Words& w : images) {
    put(w.width);
    put(w.height);
    put(w.channels);
    out.write(reinterpret_cast<const char*>(w.data.data()), std::streamsize(w.data.size() * sizeof(std::uint32_t)));
  }
  out.close();
  return bool(out);
}

// Empty on success, else what is wrong with the file.
inline std::string readWords(const std::string& path, std::vector<Words>& images) {
  images.clear();
  std::ifstream in(path, std::ios::binary);
  if (!in) return "cannot open " + path;
  auto get = [&](std::uint32_t& v) { return bool(in.read(reinterpret_cast<char*>(&v), sizeof v)); };
  std::uint32_t magic = 0, count = 0;
  if (!get(magic) || magic != kMagic || !get(count)) return path + " is not a walkthrough oracle file";
  for (std::uint32_t i = 0; i < count; ++i) {
    Words w;
    if (!get(w.width) || !get(w.height) || !get(w.channels)) return path + ": image " + std::to_string(i) + " is cut";
    const std::uint64_t n = std::uint64_t(w.width) * w.height * w.channels;
    if (n > (std::uint64_t(1) << 26)) return path + ": image " + std::to_string(i) + " is implausibly large";
    w.data.resize(std::size_t(n));
    if (!in.read(reinterpret_cast<char*>(w.data.data()), std::streamsize(n * sizeof(std::uint32_t))))
      return path + ": image " + std::to_string(i) + " is cut";
    images.push_back(std::move(w));
  }
  return {};
}

}  // namespace sao::walkthrough
