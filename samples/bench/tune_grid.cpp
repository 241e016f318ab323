#include "tune_grid.h"

#include <cstdio>
#include <cstdlib>

#include "sao/presets.h"

namespace sao::bench {

const std::vector<std::string> kTunedSettings = {"samples",           "blur_radius",        "blur_stride",
                                                 "use_z_hierarchy",   "mip_switch_log2",    "resolution_divisor",
                                                 "blur_edge_sharpness", "estimator",        "slices",
                                                 "thickness",         "thickness_model",  "blur_edge_slope",
                                                 "blur_edge_relative"};

std::vector<Candidate> tuneGrid(bool quick) {
  struct Blur {
    int radius, stride;
  };
  const std::vector<int> divisors = quick ? std::vector<int>{1, 2} : std::vector<int>{1, 2, 4};
  const std::vector<Blur> blurs = quick ? std::vector<Blur>{{0, 1}, {3, 2}}
                                        : std::vector<Blur>{{0, 1}, {1, 1}, {2, 1}, {2, 2}, {3, 2}, {4, 1}};
  const std::vector<int> samples = quick ? std::vector<int>{4, 16, 64} : std::vector<int>{3, 4, 6, 8, 11, 16, 24, 32, 48, 64};
  std::vector<Candidate> out;
  for (int d : divisors) {
    // log2 q': 8 and 16 px everywhere; 32 px (nearly level 0 for every tap) at full resolution only,
    // where projected radii are largest.
    std::vector<int> hierarchy{3, 4};
    if (!quick && d == 1) hierarchy.push_back(5);
    for (int q : hierarchy)
      for (const Blur& b : blurs)
        for (int s : samples) {
          Candidate c{"grid", "", Settings{}, Extra::None};
          c.settings.resolution_divisor = d;
          c.settings.use_z_hierarchy = true;
          c.settings.mip_switch_log2 = q;
          c.settings.blur_radius = b.radius;
          c.settings.blur_stride = b.stride;
          c.settings.samples = s;
          out.push_back(c);
        }
  }
  // The visibility estimator (estimator 1, docs/effect-math.md 5.9): its own knobs (slices, the
  // thickness: constant 0.1 m, or from width with a 0.3 m or 1 m cap) over a coarser grid of the
  // shared ones (q' = 16 px; the blurs that hide its per-pixel rotation), 378 points (quick: 2,
  // from width up to 0.3 m). A constant 0.3 m walls in thin objects (BENCHMARKS: thin's (d) 0.30
  // from (a)); from width, the 1 m cap suits sphere-plane, 0.3 m sponza-like.
  const std::vector<Blur> visBlurs = quick ? std::vector<Blur>{{3, 2}} : std::vector<Blur>{{1, 1}, {2, 1}, {3, 2}};
  const std::vector<int> visSamples = quick ? std::vector<int>{16, 64} : std::vector<int>{8, 12, 16, 24, 32, 48, 64};
  const std::vector<int> visSlices = quick ? std::vector<int>{2} : std::vector<int>{2, 4};
  struct Thickness {
    int model;  // thickness_model
    float cap;  // thickness
  };
  const std::vector<Thickness> thicknesses = quick ? std::vector<Thickness>{{1, 0.3f}}
                                                   : std::vector<Thickness>{{0, 0.1f}, {1, 0.3f}, {1, 1.0f}};
  for (int d : quick ? std::vector<int>{1} : divisors)
    for (const Thickness& t : thicknesses)
      for (int sl : visSlices)
        for (const Blur& b : visBlurs)
          for (int s : visSamples) {
            Candidate c{"grid", "", Settings{}, Extra::None};
            c.settings.estimator = 1;
            c.settings.thickness = t.cap;
            c.settings.thickness_model = t.model;
            c.settings.slices = sl;
            c.settings.resolution_divisor = d;
            c.settings.use_z_hierarchy = true;
            c.settings.mip_switch_log2 = 4;
            c.settings.blur_radius = b.radius;
            c.settings.blur_stride = b.stride;
            c.settings.samples = s;
            out.push_back(c);
          }
  return out;
}

Settings untunedMedium() {
  Settings s;
  s.samples = 11, s.blur_radius = 3, s.blur_stride = 2, s.use_z_hierarchy = true, s.mip_switch_log2 = 3;
  s.resolution_divisor = 1;
  s.blur_edge_slope = false;  // the blur as it was: the time unit and the blotch baseline stay put
  return s;
}

Settings untunedDefaults() {
  Settings s = untunedMedium();
  s.blur_radius = 4;
  return s;
}

Candidate timeAnchor(std::size_t index) {
  return {"anchor", "medium-" + std::to_string(index), untunedMedium(), Extra::None};
}

bool isTimeAnchor(const std::string& kind, const std::string& name) {
  return kind == "anchor" || (kind == "unit" && name == "untuned-medium");
}

std::vector<Candidate> tuneReferences() {
  std::vector<Candidate> out{{"unit", "untuned-medium", untunedMedium(), Extra::None},
                             {"unit", "untuned-defaults", untunedDefaults(), Extra::None}};
  for (const PresetInfo& p : presets()) out.push_back({"preset", std::string(p.name), presetSettings(p.preset), Extra::None});
  Settings baseline = untunedMedium();
  baseline.use_z_hierarchy = false;
  out.push_back({"baseline", "alchemyao-style", baseline, Extra::Normals});
  return out;
}

std::string tunedSettingValue(const Settings& s, const std::string& name) {
  char b[32];
  if (name == "samples") return std::to_string(s.samples);
  if (name == "blur_radius") return std::to_string(s.blur_radius);
  if (name == "blur_stride") return std::to_string(s.blur_stride);
  if (name == "use_z_hierarchy") return s.use_z_hierarchy ? "true" : "false";
  if (name == "mip_switch_log2") return std::to_string(s.mip_switch_log2);
  if (name == "resolution_divisor") return std::to_string(s.resolution_divisor);
  if (name == "estimator") return std::to_string(s.estimator);
  if (name == "slices") return std::to_string(s.slices);
  if (name == "thickness_model") return std::to_string(s.thickness_model);
  if (name == "thickness") {
    std::snprintf(b, sizeof b, "%g", double(s.thickness));
    return b;
  }
  if (name == "blur_edge_sharpness") {
    std::snprintf(b, sizeof b, "%g", double(s.blur_edge_sharpness));
    return b;
  }
  if (name == "blur_edge_slope") return s.blur_edge_slope ? "true" : "false";
  if (name == "blur_edge_relative") {
    std::snprintf(b, sizeof b, "%g", double(s.blur_edge_relative));
    return b;
  }
  return "";
}

bool setTunedSetting(Settings& s, const std::string& name, const std::string& value) {
  if (name == "use_z_hierarchy" || name == "blur_edge_slope") {
    if (value != "true" && value != "false") return false;
    (name == "use_z_hierarchy" ? s.use_z_hierarchy : s.blur_edge_slope) = value == "true";
    return true;
  }
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end) return false;
  if (name == "blur_edge_sharpness" || name == "blur_edge_relative") {
    (name == "blur_edge_sharpness" ? s.blur_edge_sharpness : s.blur_edge_relative) = float(v);
    return true;
  }
  if (name == "thickness") {
    s.thickness = float(v);
    return true;
  }
  const int i = int(v);
  if (double(i) != v) return false;
  if (name == "samples") s.samples = i;
  else if (name == "blur_radius") s.blur_radius = i;
  else if (name == "blur_stride") s.blur_stride = i;
  else if (name == "mip_switch_log2") s.mip_switch_log2 = i;
  else if (name == "resolution_divisor") s.resolution_divisor = i;
  else if (name == "estimator") s.estimator = i;
  else if (name == "slices") s.slices = i;
  else if (name == "thickness_model") s.thickness_model = i;
  else return false;
  return true;
}

std::string settingsWords(const Settings& s) {
  std::string out;
  for (const std::string& name : kTunedSettings) {
    if (name == "mip_switch_log2" && !s.use_z_hierarchy) continue;  // unused without the hierarchy
    if ((name == "slices" || name == "thickness" || name == "thickness_model") && s.estimator == 0)
      continue;  // inert (effect/sao.glsl)
    if (name == "estimator" && s.estimator == 0) continue;  // the default: preset lines as before
    const bool blurEdge = name == "blur_edge_sharpness" || name == "blur_edge_slope" || name == "blur_edge_relative";
    if (blurEdge && tunedSettingValue(s, name) == tunedSettingValue(Settings{}, name)) continue;  // the default
    out += (out.empty() ? "" : " ") + name + "=" + tunedSettingValue(s, name);
  }
  return out;
}

std::string describeThickness(const Settings& s) {
  char t[64];
  std::snprintf(t, sizeof t, "thickness %s%g m", s.thickness_model == 1 ? "from width up to " : "", double(s.thickness));
  return t;
}

std::string describeSettings(const Settings& s) {
  std::string d = std::to_string(s.samples) + " taps, 2x2";
  if (s.estimator == 1) {
    d = "visibility (" + std::to_string(s.slices) + " slices, " + describeThickness(s) + "), " + d;
  }
  if (s.blur_radius == 0) d += ", no blur";
  else {
    d += " + " + std::to_string(2 * s.blur_radius + 1) + "-tap blur (stride " + std::to_string(s.blur_stride);
    if (s.blur_edge_relative > 0.0f) {
      char e[48];
      std::snprintf(e, sizeof e, ", edge 1/%g of z", double(s.blur_edge_relative));
      d += e;
    }
    d += ")";
  }
  if (s.use_z_hierarchy) d += ", z hierarchy (q' = " + std::to_string(1 << s.mip_switch_log2) + " px)";
  else d += ", no z hierarchy";
  if (s.resolution_divisor == 1) d += ", full resolution";
  else d += ", 1/" + std::to_string(s.resolution_divisor) + " resolution";
  return d;
}

}  // namespace sao::bench
