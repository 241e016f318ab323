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
// hierarchy q' = 2^3, 2^4 px (and 2^5 at divisor 1), then blur (radius, stride) {(0,1), (1,1), (2,1),
// (2,2), (3,2), (4,1)}, then samples {3, 4, 6, 8, 11, 16, 24, 32, 48, 64}: 420 points. Every other
// setting keeps its default (the blur's depth edge too: along the slope since 2026-12-08, 10/m).
// Every point keeps the z hierarchy: on llvmpipe scattered level-0 taps are cheap (the CPU's caches
// hold the whole z buffer), but on a GPU the hierarchy is what keeps SAO's cost flat in the radius
// (the paper's 7x, the traffic model's 4x from L2), so presets tuned without it on this machine's
// clock would be slow where users run them. The first grid (2026-12-02: q' {8, 16, off} x blur
// {(0,1), (2,2), (3,2), (4,1)}, itself pruned from 840 points) lacked the light blurs (1,1) and
// (2,1) that the accurate end needs.
// `quick`: samples {4, 16, 64} x blur {(0,1), (3,2)} x q' {8, 16} x divisor {1, 2}.
// Then the visibility estimator (estimator 1): divisor {1, 2, 4} x thickness {constant 0.1 m, from
// width (thickness_model 1) up to 0.3 m, up to 1 m} x slices {2, 4} x blur {(1,1), (2,1), (3,2)} x
// samples {8, 12, 16, 24, 32, 48, 64} at q' = 16 px, 378 points (quick: samples {16, 64} at divisor
// 1, from width up to 0.3 m, 2 slices, blur (3,2)). Its blotch, high-frequency and silhouette
// figures (and its error with --objective c) are against its own converged value
// (visibility_converged.h), not (c).
std::vector<Candidate> tuneGrid(bool quick);

// The time unit and the blotch baseline, fixed: the medium preset and the settings' defaults as they
// were before the first tuning (2026-12-02; the appearance settings are today's defaults; the blur
// compares a tap with the centre's z, blur_edge_slope false). Presets tuned against them do not move
// the unit they were tuned in, so a rerun after adopting them finds the same chain.
Settings untunedMedium();    // 11 taps, 2x2 + 7-tap blur (stride 2), q' = 8 px, full resolution
Settings untunedDefaults();  // 11 taps, 2x2 + 9-tap blur (stride 2), q' = 8 px, full resolution

// untunedMedium() measured again between grid points (kind "anchor", name "medium-<index>"): the
// time unit is interpolated between anchors, so that the machine's drift over a long run cancels.
Candidate timeAnchor(std::size_t index);
// A measurement of the time unit: a time anchor, or the untuned medium's own row (candidate 0, the
// first anchor). tune.csv keeps one such row per session (tune_csv.h).
bool isTimeAnchor(const std::string& kind, const std::string& name);

// The two untuned rows (kind "unit": "untuned-medium", the first anchor, and "untuned-defaults"),
// today's presets (effect/sao.glsl, declaration order), then the AlchemyAO-style baseline: the
// untuned medium without the z hierarchy, given the ray-cast normals (the radius section's third curve).
std::vector<Candidate> tuneReferences();

// The tuned settings as `k=v` words, in kTunedSettings order ("samples=11 blur_radius=3 ..."), as a
// `#pragma sao preset` line lists them: mip_switch_log2 only with the hierarchy, blur_edge_sharpness,
// blur_edge_slope and blur_edge_relative only when not the default.
std::string settingsWords(const Settings& s);
// The tuned settings' names, the columns of tune.csv that describe a candidate.
extern const std::vector<std::string> kTunedSettings;
// Reads one tuned setting's value as written by settingsWords ("true", "3", "10"); false if `name`
// is not a tuned setting or the value does not parse.
bool setTunedSetting(Settings& s, const std::string& name, const std::string& value);
std::string tunedSettingValue(const Settings& s, const std::string& name);

// The visibility estimator's thickness: "thickness 0.1 m", "thickness from width up to 0.3 m".
std::string describeThickness(const Settings& s);

// A preset's summary: "11 taps, 2x2 + 7-tap blur (stride 2), z hierarchy (q' = 8 px), full resolution"
// ("2x2, no blur" without the blur).
std::string describeSettings(const Settings& s);

}  // namespace sao::bench
