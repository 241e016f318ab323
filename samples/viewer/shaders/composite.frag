#version 450
// The viewer's composite: the AO, the scene lit with and without it (hemisphere environment light
// from normals rebuilt from depth), a split view, the raw AO before the blur, a csz MIP level,
// the rebuilt normals, |AO - reference| as a heat map, or the AO at full | reduced resolution. Texel rows of every input are in ndc-y
// order (row 0 at ndc y = -1); modes.z flips the window's y when the framebuffer is top-down.
layout(std140, binding = 0) uniform CompositeParams {
  vec4 projInfo;    // camera-space x = z * (projInfo.x * px + projInfo.y), y = z * (projInfo.z * py + projInfo.w); no z when orthographic
  vec4 depthModel;  // z = c0 / (d * c1 + c2); w: the stored depth of the far plane (sky)
  vec4 worldUp;     // world up in camera space
  vec4 display;     // near and far distance of the csz view, error of full heat, split x in pixels
  ivec4 modes;      // view mode, csz level, flip y, reference present
  ivec4 extra;      // guard band, viewport height, raw AO present, csz levels
  ivec4 projection; // x: 1 orthographic (z = d * c1 + c2, and x, y without the factor z)
  ivec4 legend;     // the error view's colour bar: x0, y0, x1, y1 in window pixels from the bottom left
} P;
layout(binding = 1) uniform sampler2D depthTex;
layout(binding = 2) uniform sampler2D aoTex;
layout(binding = 3) uniform sampler2D aoRawTex;
layout(binding = 4) uniform sampler2D cszTex;
layout(binding = 5) uniform sampler2D referenceTex;
layout(binding = 6) uniform sampler2D aoReducedTex;  // split-resolution: aoTex is the full-resolution AO
layout(location = 0) out vec4 fragColor;

const int kAo = 0, kLit = 1, kLitNoAo = 2, kSplit = 3, kRawAo = 4, kZMip = 5, kNormals = 6, kError = 7, kSplitResolution = 8;
const vec3 kSky = vec3(0.55, 0.7, 1.0), kGround = vec3(0.25, 0.2, 0.15);
const float kAlbedo = 0.75;

bool finite3(vec3 v) { return all(lessThan(abs(v), vec3(1e30))); }

vec3 positionAt(ivec2 t) {
  t = clamp(t, ivec2(0), textureSize(depthTex, 0) - 1);
  float d = texelFetch(depthTex, t, 0).r;
  bool ortho = P.projection.x != 0;
  float z = ortho ? d * P.depthModel.y + P.depthModel.z : P.depthModel.x / (d * P.depthModel.y + P.depthModel.z);
  vec2 px = vec2(t) + 0.5;
  float k = ortho ? 1.0 : z;
  return vec3(k * (P.projInfo.x * px.x + P.projInfo.y), k * (P.projInfo.z * px.y + P.projInfo.w), z);
}

// The neighbour difference with the smaller |dz| (skips depth edges), ignoring sky neighbours.
vec3 pickSide(vec3 forward, vec3 backward) {
  bool f = finite3(forward), b = finite3(backward);
  if (f && b) return abs(forward.z) < abs(backward.z) ? forward : backward;
  return f ? forward : (b ? backward : vec3(0.0));
}

vec3 normalAt(ivec2 t) {
  vec3 c = positionAt(t);
  vec3 dx = pickSide(positionAt(t + ivec2(1, 0)) - c, c - positionAt(t - ivec2(1, 0)));
  vec3 dy = pickSide(positionAt(t + ivec2(0, 1)) - c, c - positionAt(t - ivec2(0, 1)));
  vec3 n = cross(dx, dy);
  if (!(dot(n, n) > 0.0) || !finite3(n)) return vec3(0.0, 0.0, 1.0);
  n = normalize(n);
  return dot(n, P.projection.x != 0 ? vec3(0.0, 0.0, -1.0) : c) > 0.0 ? -n : n;
}

vec3 toSrgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// Black -> red -> yellow -> white.
vec3 heat(float t) { return clamp(vec3(3.0 * t, 3.0 * t - 1.0, 3.0 * t - 2.0), 0.0, 1.0); }

vec3 lit(ivec2 t, bool sky, float ao) {
  if (sky) return kSky;
  float s = 0.5 + 0.5 * dot(normalAt(t), P.worldUp.xyz);
  return kAlbedo * (s * kSky + (1.0 - s) * kGround) * ao;
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  if (P.modes.z != 0) p.y = P.extra.y - 1 - p.y;
  bool inLegend = all(greaterThanEqual(p, P.legend.xy)) && all(lessThan(p, P.legend.zw));
  p = clamp(p, ivec2(0), textureSize(depthTex, 0) - 2 * P.extra.x - 1);  // a window briefly larger than the images
  ivec2 t = p + ivec2(P.extra.x);
  int mode = P.modes.x;
  bool sky = texelFetch(depthTex, t, 0).r == P.depthModel.w;
  float ao = clamp(texelFetch(aoTex, p, 0).r, 0.0, 1.0);
  vec3 color;
  if (mode == kAo) {
    color = vec3(ao);
  } else if (mode == kRawAo) {
    color = vec3(clamp(P.extra.z != 0 ? texelFetch(aoRawTex, p, 0).r : ao, 0.0, 1.0));
  } else if (mode == kZMip) {
    int level = clamp(P.modes.y, 0, max(P.extra.w - 1, 0));
    float z = texelFetch(cszTex, t >> level, level).r;
    if (!(z < 0.0)) {
      color = vec3(0.08, 0.1, 0.25);  // sky: csz holds +0.0
    } else {
      float v = (log(-z) - log(P.display.x)) / (log(P.display.y) - log(P.display.x));
      color = vec3(1.0 - clamp(v, 0.0, 1.0));
    }
  } else if (mode == kNormals) {
    color = sky ? vec3(0.0) : normalAt(t) * 0.5 + 0.5;
  } else if (mode == kError) {
    if (P.modes.w == 0) {
      color = vec3(ao) * vec3(0.6, 0.6, 0.8);  // no reference yet: the AO, tinted
    } else {
      float e = abs(ao - texelFetch(referenceTex, p, 0).r);
      color = sky ? vec3(0.0) : heat(e / P.display.z);
      // The colour bar: 0 at the bottom, the error at full heat (display.z) at the top.
      if (inLegend) color = heat((float(p.y - P.legend.y) + 0.5) / float(P.legend.w - P.legend.y));
    }
  } else if (mode == kSplitResolution) {
    float reduced = clamp(texelFetch(aoReducedTex, p, 0).r, 0.0, 1.0);
    color = vec3(gl_FragCoord.x >= P.display.w ? reduced : ao);
    // An orange divider: white would vanish against unoccluded floor and sky.
    if (abs(gl_FragCoord.x - P.display.w) < 1.0) color = vec3(1.0, 0.45, 0.1);
  } else {
    bool withAo = mode == kLit || (mode == kSplit && gl_FragCoord.x >= P.display.w);
    color = toSrgb(lit(t, sky, withAo ? ao : 1.0));
    if (mode == kSplit && abs(gl_FragCoord.x - P.display.w) < 1.0) color = vec3(1.0);
  }
  fragColor = vec4(color, 1.0);
}
