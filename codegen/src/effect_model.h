// The effect as declared by `#pragma sao` directives: the one source of truth.
#pragma once
#include "formats.h"
#include <optional>
#include <string>
#include <vector>

#include "source_loader.h"

namespace sao::codegen {

enum class ScalarType { Float, Int, Bool };

struct Setting {
  SourceLoc loc;
  ScalarType type = ScalarType::Float;
  std::string name;
  double defaultValue = 0;
  double minValue = 0;
  double maxValue = 1;
  std::vector<double> allowed;  // values=[a,b,...] (int only): the only values accepted, ascending
  std::string unit;
  std::string doc;
};

struct Constant {
  SourceLoc loc;
  std::string type;  // "int", "uint", "float"
  std::string name;
  std::string value;  // GLSL literal, validated for the type
  std::string doc;
};

// What picks a variant's value when the effect is planned (`select=`).
enum class VariantSelect {
  Default,  // no select=: always the default value
  Setting,  // select=SETTING: a bool setting, 1 when true
  Input,    // select=input:RESOURCE: 1 when the user supplies that kind=input resource
  Output,   // select=output:RESOURCE: the index, in the kind=output resource's formats=, of its image's format
  Multisampled,  // select=multisampled:RESOURCE: 1 when the user's kind=input resource has more than one sample
                 // per texel; the passes that list the variant then read it as sampler2DMS
};

struct Variant {
  SourceLoc loc;
  std::string name;
  std::vector<int> values;
  int defaultValue = 0;
  VariantSelect select = VariantSelect::Default;
  int selectIndex = -1;  // setting or resource index
  std::string doc;
};

struct Exclusion {
  SourceLoc loc;
  std::vector<std::pair<int, int>> terms;  // (variant index, value)
  std::string reason;
};

enum class ResourceKind { Input, Image, Output };

// Channels of a colour format name (r*: 1, rg*: 2, rgba*: 4).
inline int formatChannels(const std::string& format) {
  const auto f = findFormat(format);
  return f ? int(f->channels) : 0;
}

struct Resource {
  SourceLoc loc;
  std::string name;
  ResourceKind kind = ResourceKind::Image;
  std::string format;      // r32f, rg32f, r16f, rg16f, rgba16f, r8, rgba8, depth
  // formats=[...]: kind=output, every format the output may have, `format` among them (the
  // variant with select=output:NAME picks one, and each pass writing it lists that variant); a
  // colour kind=input, the formats it accepts (empty: any colour format with enough channels).
  std::vector<std::string> formats;
  // format_when=VARIANT:F (kind=image): the image has format F instead of `format` where that
  // variant is non-zero (rg16f intermediates); every pass writing it lists the variant.
  int formatWhenVariant = -1;
  std::string formatWhen;
  bool fullMipChain = false;  // mips=auto
  bool inputExtent = false;   // extent=input: the depth input's size (viewport + guard band)
  int scaleDenominator = 1;   // scale=1/N of the base extent
  int divideBy = -1;          // divide_by=SETTING: the AO extent over that int setting, rounded up
  int whenVariant = -1;       // exists only when this variant is non-zero
  // history=true (kind=image, single level): kept across frames in two images that trade places
  // every frame; a pass's read sees the image the previous frame wrote, its write this frame's.
  bool history = false;
  std::string doc;
};

struct BlockMember {
  SourceLoc loc;
  std::string glslType;
  std::string name;
  int arraySize = 0;  // 0 = not an array
  int offset = 0;
  int size = 0;       // bytes the member occupies (including array stride padding)
};

struct ParamBlock {
  SourceLoc loc;  // the `#pragma sao block` line
  std::string name;
  std::vector<BlockMember> members;
  int size = 0;  // rounded up to 16 bytes
};

enum class CompareOp { Eq, Ne, Lt, Le, Gt, Ge };

// `SETTING OP LITERAL` on one int or bool setting (skip_when=, alias_when=).
struct SettingCondition {
  int setting = -1;
  CompareOp op = CompareOp::Eq;
  double value = 0;
  std::string text;  // as written, for messages
};

// `#pragma sao derived NAME when=TERM&&TERM... "doc"`: a bool that plan() computes from the settings,
// true when every term (a condition on an int or bool setting) holds. Conditions (skip_when=,
// alias_when=) name it like a bool setting; the user cannot set it. In a SettingCondition it is
// setting index settings.size() + its index in Effect::derived.
struct DerivedSetting {
  SourceLoc loc;
  std::string name;
  std::vector<SettingCondition> terms;
  std::string doc;
};

// `#pragma sao inert SETTING when=COND "why"`: SETTING has no effect while COND holds (its value
// reaches no pass that runs then). COND as in skip_when=, on any setting, a float one too, or a
// derived setting. Programs refuse a setting the user gave that a rule makes inert.
// `#pragma sao refuse SETTING when=COND "why"` has the same shape: plan() refuses SETTING at any
// value but its default while COND holds (a feature that the passes planned then cannot carry).
struct InertRule {
  SourceLoc loc;
  int setting = -1;
  SettingCondition when;
  std::string whenText;  // COND in words, a derived setting's terms spelled out: "fade_end = 0"
  std::string fixText;   // what makes COND false: "fade_end > 0"
  std::string doc;
};

// A binding of `declared` that `serving` fills instead (the output of a skipped pass).
struct ResourceAlias {
  int declared = -1;  // resource indices
  int serving = -1;
};

struct Pass {
  SourceLoc loc;
  std::string name;
  std::string entry;
  int localX = 8, localY = 8;
  int texelsX = 1, texelsY = 1;  // texels=WxH: texels of the first written level per invocation
  std::vector<int> reads;    // resource indices
  std::vector<int> writes;   // resource indices
  std::vector<int> variants; // variant indices, effect order
  // levels=A..B: the pass writes levels A..B of the MIP chains it writes, each as an image array
  // out_<res>[B - A + 1] (slot j = level A + j); reading one of them, it sees level A - 1 alone.
  int firstLevel = 0;
  int levelSlots = 0;  // B - A + 1; 0 without levels=
  std::optional<SettingCondition> skipWhen;   // the pass does not run when this holds
  std::optional<SettingCondition> aliasWhen;  // `aliases` apply when this holds
  std::vector<ResourceAlias> aliases;
  std::string doc;
  std::vector<SourceLine> code;  // the pass section's GLSL
};

// A named set of setting values; settings it does not list keep their defaults.
struct Preset {
  SourceLoc loc;
  std::string name;  // lower-case identifier; the C++ enumerator upper-cases its first letter
  std::vector<std::pair<int, double>> values;  // (setting index, value), in source order
  std::string doc;
};

// `#pragma sao target gles storage=[F:G,...] refuse=[F,...] "why"`: how the effect's storage images
// map onto OpenGL ES 3.1, which stores fewer formats (formats.h, esStorage). An image of format F
// takes G there (the images the effect owns, and an output the effect allocates); a refused F (a
// caller's output format only) has no GLES form, and the GLES executor refuses that output.
struct StorageSubstitute {
  std::string from, to;
};
struct TargetRule {
  SourceLoc loc;
  std::string target;  // "gles"
  std::vector<StorageSubstitute> storage;
  std::vector<std::string> refused;
  std::string doc;
};

struct Effect {
  SourceLoc loc;
  std::string name;
  int version = 0;
  std::vector<Setting> settings;
  std::vector<DerivedSetting> derived;
  std::vector<InertRule> inert;
  std::vector<InertRule> refusals;  // `refuse` rules
  std::vector<Constant> constants;
  std::vector<Variant> variants;
  std::vector<Exclusion> exclusions;
  std::vector<Resource> resources;
  std::optional<ParamBlock> block;
  std::vector<Pass> passes;
  std::vector<Preset> presets;
  std::optional<TargetRule> gles;  // no directive: formats GLES cannot store are refused there
  std::vector<SourceLine> commonCode;  // GLSL outside pass sections, directives removed
};

}  // namespace sao::codegen
