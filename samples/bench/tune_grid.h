// sao-bench --tune: what it evaluates. The fixed candidate grid (the settings that trade time for
// error vs reference (c)), today's presets and the AlchemyAO-style baseline, each as one Candidate
// with a key that names it in tune.csv.
#pragma once
#include <string>
#include <vector>

#include "scene_cache.h"
#include "sao/settings.h"

namespace sao::bench {

struct Candidate {
  std::string kind;  // "grid", "preset" (today's, by name) or "baseline"
  std::string name;  // the preset's name, "alchemyao-style", or empty for a grid point
  Settings settings;
  Extra extra = Extra::None;  // the baseline is given normals (NORMALS_SUPPLIED=1)
};

// The grid in its documented order, outermost first: resolution_divisor {1, 2, 4}, then the z
// hierarchy {q' = 2^3, 2^4, off}, then blur (radius, stride) {(0,1), (2,2), (3,2), (4,1)}, then
// samples {3, 4, 6, 8, 11, 16, 24, 32, 48, 64}: 360 points. Every other setting keeps its default
// (blur_edge_sharpness included). Pruned from q' {2^2, 2^3, 2^4, off} x blur {(0,1), (2,2), (3,2),
// (4,2), (4,1), (6,1), (8,1)} (840 points, over an hour here): in a first partial run over the
// full-resolution q' = 2^2 and 2^3 points, blur (6,1) and (8,1) never reached the front, and blur
// (4,2) and q' = 2^2 once, together, at 3 taps (that run's times drifted up to 2x: a rough guide). `quick`: samples {4, 16, 64} x blur {(0,1), (3,2)} x {q' = 2^3, off} x divisor {1, 2}.
std::vector<Candidate> tuneGrid(bool quick);

// The medium preset measured again between grid points (kind "anchor", name "medium-<index>"):
// the time unit is interpolated between anchors, so that the machine's drift over a long run cancels.
Candidate timeAnchor(std::size_t index);

// Today's presets (effect/sao.glsl, declaration order), then the AlchemyAO-style baseline: the
// medium preset without the z hierarchy, given the ray-cast normals (the radius section's third curve).
std::vector<Candidate> tuneReferences();

// The tuned settings as `k=v` words, in kTunedSettings order ("samples=11 blur_radius=3 ..."), as a
// `#pragma sao preset` line lists them: mip_switch_log2 only with the hierarchy, blur_edge_sharpness
// only when not the default.
std::string settingsWords(const Settings& s);
// The tuned settings' names, the columns of tune.csv that describe a candidate.
extern const std::vector<std::string> kTunedSettings;
// Reads one tuned setting's value as written by settingsWords ("true", "3", "10"); false if `name`
// is not a tuned setting or the value does not parse.
bool setTunedSetting(Settings& s, const std::string& name, const std::string& value);
std::string tunedSettingValue(const Settings& s, const std::string& name);

// A preset's summary: "11 taps, 2x2 + 7-tap blur (stride 2), z hierarchy (q' = 8 px), full resolution"
// ("2x2, no blur" without the blur).
std::string describeSettings(const Settings& s);

}  // namespace sao::bench
