#include "directive_parser.h"

#include <algorithm>
#include <map>
#include <regex>
#include <set>

#include "effect_rules.h"
#include "formats.h"
#include "std140.h"
#include "target_rules.h"
#include "text_values.h"

namespace sao::codegen {
namespace {

// A colour format: one a pass may store to (formats.h: every format but depth).
bool isColourFormat(const std::string& name) {
  const auto f = findFormat(name);
  return f && f->colour;
}

// One `#pragma sao` line: words, key=value attributes and an optional trailing doc string.
struct Directive {
  SourceLoc loc;
  std::string kind;
  std::vector<std::string> words;            // positional, after the kind
  std::vector<std::pair<std::string, std::string>> attrs;  // in order
  std::string doc;
  bool hasDoc = false;
};

bool tokenize(const SourceLine& line, const std::string& rest, Directive& d, Diagnostics& diags) {
  d.loc = line.loc;
  size_t i = 0;
  std::vector<std::string> tokens;
  while (i < rest.size()) {
    if (rest[i] == ' ' || rest[i] == '\t') {
      ++i;
      continue;
    }
    if (rest.compare(i, 2, "//") == 0) break;
    if (rest[i] == '"') {
      const size_t close = rest.find('"', i + 1);
      if (close == std::string::npos) {
        diags.error(line.loc, "unterminated string in directive");
        return false;
      }
      d.doc = rest.substr(i + 1, close - i - 1);
      d.hasDoc = true;
      i = close + 1;
      const size_t next = rest.find_first_not_of(" \t", i);
      if (next != std::string::npos && rest.compare(next, 2, "//") != 0) {
        diags.error(line.loc, "text after the doc string: the doc string must come last");
        return false;
      }
      break;
    }
    const size_t end = rest.find_first_of(" \t\"", i);
    tokens.push_back(rest.substr(i, end == std::string::npos ? std::string::npos : end - i));
    i = end == std::string::npos ? rest.size() : end;
  }
  if (tokens.empty()) {
    diags.error(line.loc, "empty '#pragma sao' directive");
    return false;
  }
  d.kind = tokens[0];
  for (size_t t = 1; t < tokens.size(); ++t) {
    const size_t eq = tokens[t].find('=');
    if (eq == std::string::npos) d.words.push_back(tokens[t]);
    else d.attrs.emplace_back(tokens[t].substr(0, eq), tokens[t].substr(eq + 1));
  }
  return true;
}

class Parser {
 public:
  Parser(const LoadedSource& src, Diagnostics& diags) : src_(src), diags_(diags) {}

  Effect run() {
    static const std::regex pragmaRe(R"(^\s*#\s*pragma\s+sao\b(.*)$)");
    Pass* open = nullptr;
    for (size_t i = 0; i < src_.lines.size(); ++i) {
      const SourceLine& line = src_.lines[i];
      std::smatch m;
      if (!std::regex_match(line.text, m, pragmaRe)) {
        if (open) open->code.push_back(line);
        else effect_.commonCode.push_back(line);
        continue;
      }
      Directive d;
      if (!tokenize(line, m[1].str(), d, diags_)) continue;
      if (open && d.kind != "end") {
        diags_.error(d.loc, "directive '" + d.kind + "' inside the section of pass '" + open->name +
                                "' (close it with '#pragma sao end' first)");
        continue;
      }
      if (!sawEffect_ && d.kind != "effect") {
        diags_.error(d.loc, "the first directive must be '#pragma sao effect NAME version=N'");
        sawEffect_ = true;  // report once
      }
      if (d.kind == "effect") parseEffectDirective(d);
      else if (d.kind == "setting") parseSetting(d);
      else if (d.kind == "constant") parseConstant(d);
      else if (d.kind == "variant") parseVariant(d);
      else if (d.kind == "exclude") pendingExcludes_.push_back(d);
      else if (d.kind == "resource") parseResource(d);
      else if (d.kind == "block") parseBlock(d, i + 1);
      else if (d.kind == "pass") open = parsePass(d);
      else if (d.kind == "preset") pendingPresets_.push_back(d);
      else if (d.kind == "target") parseTargetRule(effect_, d.loc, d.words, d.attrs, d.doc, d.hasDoc, diags_);
      else if (d.kind == "derived") {
        // Parsed once every setting is known (below); its name is claimed here, in source order.
        if (d.words.size() != 1 || nameIsNew(d, "derived setting", d.words[0])) pendingDerived_.push_back(d);
      }
      else if (d.kind == "inert" || d.kind == "refuse") pendingSettingRules_.push_back(d);  // once every setting is known
      else if (d.kind == "end") {
        if (!open) diags_.error(d.loc, "'#pragma sao end' without an open pass section");
        open = nullptr;
      } else {
        diags_.error(d.loc, "unknown directive '" + d.kind + "'");
      }
    }
    if (open) diags_.error(open->loc, "pass '" + open->name + "' is not closed by '#pragma sao end'");
    const SourceLoc fileLoc{src_.files.empty() ? std::string() : src_.files.front(), 0};
    if (!sawEffect_) diags_.error(fileLoc, "no '#pragma sao effect' directive: not an annotated effect");
    for (const auto& d : pendingExcludes_) parseExclude(d);
    for (const auto& d : pendingDerived_) parseDerived(effect_, d.loc, d.words, d.attrs, d.doc, d.hasDoc, diags_);
    for (const auto& d : pendingSettingRules_)
      parseSettingRule(effect_, d.kind == "refuse", d.loc, d.words, d.attrs, d.doc, d.hasDoc, diags_);
    // Rules name settings and resources, which may be declared after the variant or pass.
    for (const auto& [v, d] : pendingSelects_) resolveVariantSelect(effect_, effect_.variants[v], d.loc, d.text, diags_);
    for (const auto& [p, d] : pendingPasses_) resolvePass(effect_.passes[p], d);
    checkPassRules(effect_, diags_);
    for (const auto& d : pendingPresets_) parsePreset(effect_, d.loc, d.words, d.attrs, d.doc, d.hasDoc, diags_);
    if (sawEffect_ && !effect_.block) diags_.error(fileLoc, "no '#pragma sao block' parameter block declared");
    if (sawEffect_ && effect_.passes.empty()) diags_.error(fileLoc, "no '#pragma sao pass' declared");
    checkExplicitBindings();
    checkTargetRules(effect_, diags_);
    return effect_;
  }

 private:
  // Attribute access with "unknown attribute" checks.
  std::map<std::string, std::string> attrs(const Directive& d, const std::set<std::string>& allowed) {
    std::map<std::string, std::string> out;
    for (const auto& [k, v] : d.attrs) {
      if (!allowed.count(k)) {
        diags_.error(d.loc, "unknown attribute '" + k + "' for '" + d.kind + "'");
        continue;
      }
      if (out.count(k)) diags_.error(d.loc, "attribute '" + k + "' given twice");
      out[k] = v;
    }
    return out;
  }

  bool nameIsNew(const Directive& d, const std::string& what, const std::string& name) {
    if (!isIdentifier(name)) {
      diags_.error(d.loc, what + " name '" + name + "' is not an identifier");
      return false;
    }
    if (names_.count(name)) {
      diags_.error(d.loc, "duplicate name '" + name + "' (first declared at line " +
                              std::to_string(names_[name].line) + ")");
      return false;
    }
    names_[name] = d.loc;
    return true;
  }

  void parseEffectDirective(const Directive& d) {
    if (sawEffectDirective_) {
      diags_.error(d.loc, "second '#pragma sao effect' directive");
      return;
    }
    sawEffect_ = sawEffectDirective_ = true;
    auto a = attrs(d, {"version"});
    effect_.loc = d.loc;
    if (d.words.size() != 1 || !isIdentifier(d.words[0])) {
      diags_.error(d.loc, "expected '#pragma sao effect NAME version=N'");
      return;
    }
    effect_.name = d.words[0];
    if (!a.count("version") || !parseInt(a["version"], effect_.version) || effect_.version < 1)
      diags_.error(d.loc, "effect needs version=N with N >= 1");
  }

  void parseSetting(const Directive& d) {
    auto a = attrs(d, {"default", "range", "values", "unit"});
    if (d.words.size() != 2) {
      diags_.error(d.loc, "expected '#pragma sao setting TYPE NAME default=V range=[MIN,MAX]|values=[A,B,...] [unit=U] \"doc\"'");
      return;
    }
    Setting s;
    s.loc = d.loc;
    s.name = d.words[1];
    if (d.words[0] == "float") s.type = ScalarType::Float;
    else if (d.words[0] == "int") s.type = ScalarType::Int;
    else if (d.words[0] == "bool") s.type = ScalarType::Bool;
    else {
      diags_.error(d.loc, "unknown setting type '" + d.words[0] + "' (expected float, int or bool)");
      return;
    }
    if (!nameIsNew(d, "setting", s.name)) return;
    s.unit = a.count("unit") ? a["unit"] : "";
    s.doc = d.doc;
    if (!d.hasDoc || d.doc.empty()) diags_.error(d.loc, "setting '" + s.name + "' has no doc string");
    if (!a.count("default")) {
      diags_.error(d.loc, "setting '" + s.name + "' has no default");
      return;
    }
    const std::string& def = a["default"];
    if (s.type == ScalarType::Bool) {
      if (a.count("range") || a.count("values")) diags_.error(d.loc, "bool setting '" + s.name + "' takes no range or values");
      if (def != "true" && def != "false") {
        diags_.error(d.loc, "default '" + def + "' of bool setting '" + s.name + "' is not true or false");
        return;
      }
      s.defaultValue = def == "true" ? 1 : 0;
      s.minValue = 0;
      s.maxValue = 1;
      effect_.settings.push_back(s);
      return;
    }
    if (a.count("values")) {
      parseAllowedValues(d, s, a);
      return;
    }
    if (!a.count("range")) {
      diags_.error(d.loc, "setting '" + s.name + "' has no range=[MIN,MAX]");
      return;
    }
    if (!readValue(d, s, def, s.defaultValue, "default")) return;
    const std::string& r = a["range"];
    const auto parts = r.size() >= 2 && r.front() == '[' && r.back() == ']' ? splitList(r.substr(1, r.size() - 2))
                                                                          : std::vector<std::string>{};
    if (parts.size() != 2) {
      diags_.error(d.loc, "range of setting '" + s.name + "' must be [MIN,MAX], got '" + r + "'");
      return;
    }
    if (!readValue(d, s, parts[0], s.minValue, "range minimum") || !readValue(d, s, parts[1], s.maxValue, "range maximum"))
      return;
    if (s.minValue > s.maxValue) {
      diags_.error(d.loc, "range of setting '" + s.name + "' is empty: " + parts[0] + " > " + parts[1]);
      return;
    }
    if (s.defaultValue < s.minValue || s.defaultValue > s.maxValue) {
      diags_.error(d.loc, "default " + def + " of setting '" + s.name + "' is outside its range " + r);
      return;
    }
    effect_.settings.push_back(s);
  }

  // values=[A,B,...] of an int setting: the only values it takes (a range would let the values
  // between them through), ascending; the range is [A, last].
  void parseAllowedValues(const Directive& d, Setting& s, std::map<std::string, std::string>& a) {
    const std::string& text = a["values"];
    if (s.type != ScalarType::Int || a.count("range")) {
      diags_.error(d.loc, "values= of setting '" + s.name + "' is for int settings without range=");
      return;
    }
    const auto parts = text.size() >= 2 && text.front() == '[' && text.back() == ']'
                           ? splitList(text.substr(1, text.size() - 2))
                           : std::vector<std::string>{};
    if (parts.empty()) {
      diags_.error(d.loc, "values of setting '" + s.name + "' must be [A,B,...], got '" + text + "'");
      return;
    }
    for (const auto& part : parts) {
      double v = 0;
      if (!readValue(d, s, part, v, "value")) return;
      if (!s.allowed.empty() && v <= s.allowed.back()) {
        diags_.error(d.loc, "values of setting '" + s.name + "' must be ascending and distinct, got '" + text + "'");
        return;
      }
      s.allowed.push_back(v);
    }
    if (!readValue(d, s, a["default"], s.defaultValue, "default")) return;
    if (std::find(s.allowed.begin(), s.allowed.end(), s.defaultValue) == s.allowed.end()) {
      diags_.error(d.loc, "default " + a["default"] + " of setting '" + s.name + "' is not one of its values " + text);
      return;
    }
    s.minValue = s.allowed.front();
    s.maxValue = s.allowed.back();
    effect_.settings.push_back(s);
  }

  bool readValue(const Directive& d, const Setting& s, const std::string& text, double& out, const char* what) {
    if (s.type == ScalarType::Int) {
      int v = 0;
      if (!parseInt(text, v)) {
        diags_.error(d.loc, std::string(what) + " '" + text + "' of int setting '" + s.name + "' is not an integer");
        return false;
      }
      out = v;
      return true;
    }
    if (!parseNumber(text, out)) {
      diags_.error(d.loc, std::string(what) + " '" + text + "' of setting '" + s.name + "' is not a finite number");
      return false;
    }
    return true;
  }

  void parseConstant(const Directive& d) {
    // Form: constant TYPE NAME=VALUE "doc" -> words {TYPE}, attrs {NAME: VALUE}
    if (d.words.size() != 1 || d.attrs.size() != 1) {
      diags_.error(d.loc, "expected '#pragma sao constant TYPE NAME=VALUE \"doc\"'");
      return;
    }
    Constant c;
    c.loc = d.loc;
    c.type = d.words[0];
    c.name = d.attrs[0].first;
    c.value = d.attrs[0].second;
    c.doc = d.doc;
    double v = 0;
    int iv = 0;
    if (c.type == "int" || c.type == "uint") {
      if (!parseInt(c.value, iv) || (c.type == "uint" && iv < 0)) {
        diags_.error(d.loc, "value '" + c.value + "' of " + c.type + " constant '" + c.name + "' is not valid");
        return;
      }
    } else if (c.type == "float") {
      if (!parseNumber(c.value, v)) {
        diags_.error(d.loc, "value '" + c.value + "' of float constant '" + c.name + "' is not a finite number");
        return;
      }
    } else {
      diags_.error(d.loc, "unknown constant type '" + c.type + "' (expected int, uint or float)");
      return;
    }
    if (!nameIsNew(d, "constant", c.name)) return;
    effect_.constants.push_back(c);
  }

  void parseVariant(const Directive& d) {
    auto a = attrs(d, {"values", "default", "select"});
    if (d.words.size() != 1) {
      diags_.error(d.loc, "expected '#pragma sao variant NAME values=[a,b,...] default=V [select=S] \"doc\"'");
      return;
    }
    Variant v;
    v.loc = d.loc;
    v.name = d.words[0];
    v.doc = d.doc;
    if (!nameIsNew(d, "variant", v.name)) return;
    const std::string vals = a.count("values") ? a["values"] : "";
    if (vals.size() < 2 || vals.front() != '[' || vals.back() != ']') {
      diags_.error(d.loc, "variant '" + v.name + "' needs values=[a,b,...]");
      return;
    }
    for (const auto& part : splitList(vals.substr(1, vals.size() - 2))) {
      int x = 0;
      if (!parseInt(part, x) || x < 0) {
        diags_.error(d.loc, "value '" + part + "' of variant '" + v.name + "' is not a non-negative integer");
        return;
      }
      for (int y : v.values)
        if (y == x) {
          diags_.error(d.loc, "value " + part + " of variant '" + v.name + "' listed twice");
          return;
        }
      v.values.push_back(x);
    }
    if (v.values.size() < 2) {
      diags_.error(d.loc, "variant '" + v.name + "' needs at least two values");
      return;
    }
    // Each pass compiles the combinations of the variants it lists (at most kMaxPassVariants); the
    // effect's whole product only bounds a list of variants that nothing could ever build. The real
    // effect has 4096 (ten two-valued variants and the output format's four): room for new inputs'
    // select=input variants (docs/adding-a-pass.md, section 6).
    constexpr std::size_t kMaxCombinations = 65536;
    std::size_t combinations = v.values.size();
    for (const Variant& other : effect_.variants) combinations *= other.values.size();
    if (v.values.size() > kMaxCombinations || combinations > kMaxCombinations) {
      diags_.error(d.loc, "variant '" + v.name + "' makes more than " + std::to_string(kMaxCombinations) +
                              " variant combinations; every combination is compiled");
      return;
    }
    v.defaultValue = v.values.front();
    if (a.count("default")) {
      if (!parseInt(a["default"], v.defaultValue) ||
          std::find(v.values.begin(), v.values.end(), v.defaultValue) == v.values.end()) {
        diags_.error(d.loc, "default '" + a["default"] + "' of variant '" + v.name + "' is not one of its values");
        return;
      }
    }
    if (a.count("select")) pendingSelects_.push_back({effect_.variants.size(), {d.loc, a["select"]}});
    effect_.variants.push_back(v);
  }

  int findVariant(const std::string& name) const {
    for (size_t i = 0; i < effect_.variants.size(); ++i)
      if (effect_.variants[i].name == name) return static_cast<int>(i);
    return -1;
  }

  int findResource(const std::string& name) const {
    for (size_t i = 0; i < effect_.resources.size(); ++i)
      if (effect_.resources[i].name == name) return static_cast<int>(i);
    return -1;
  }

  void parseExclude(const Directive& d) {
    Exclusion e;
    e.loc = d.loc;
    e.reason = d.doc;
    if (!d.hasDoc || d.doc.empty()) diags_.error(d.loc, "exclude needs a \"reason\"");
    if (!d.words.empty() || d.attrs.size() < 2) {
      diags_.error(d.loc, "expected '#pragma sao exclude VARIANT=v VARIANT=w ... \"reason\"' (two or more variants)");
      return;
    }
    for (const auto& [name, value] : d.attrs) {
      const int vi = findVariant(name);
      int x = 0;
      if (vi < 0) {
        diags_.error(d.loc, "exclude names unknown variant '" + name + "'");
        return;
      }
      const auto& vals = effect_.variants[vi].values;
      if (!parseInt(value, x) || std::find(vals.begin(), vals.end(), x) == vals.end()) {
        diags_.error(d.loc, "exclude gives variant '" + name + "' the value '" + value + "' it does not have");
        return;
      }
      e.terms.emplace_back(vi, x);
    }
    effect_.exclusions.push_back(e);
  }

  // The most combinations of its variants a pass may list (before exclusions): each is compiled twice.
  static constexpr std::size_t kMaxPassVariants = 256;

  void parseResource(const Directive& d) {
    auto a = attrs(d, {"kind", "format", "formats", "format_when", "mips", "scale", "when", "extent", "divide_by", "history"});
    if (d.words.size() != 1) {
      diags_.error(d.loc, "expected '#pragma sao resource NAME kind=K format=F [formats=[F,...]] [format_when=V:F] [mips=1|auto] [scale=1/N] [divide_by=SETTING] [when=V] [history=true] \"doc\"'");
      return;
    }
    Resource r;
    r.loc = d.loc;
    r.name = d.words[0];
    r.doc = d.doc;
    if (!nameIsNew(d, "resource", r.name)) return;
    const std::string kind = a.count("kind") ? a["kind"] : "";
    if (kind == "input") r.kind = ResourceKind::Input;
    else if (kind == "image") r.kind = ResourceKind::Image;
    else if (kind == "output") r.kind = ResourceKind::Output;
    else {
      diags_.error(d.loc, "resource '" + r.name + "' needs kind=input|image|output");
      return;
    }
    r.format = a.count("format") ? a["format"] : "";
    if (!findFormat(r.format)) {
      std::set<std::string> names;  // listed sorted
      for (const FormatFacts& f : formats()) names.insert(std::string(f.name));
      std::string list;
      for (const auto& f : names) list += (list.empty() ? "" : " ") + f;
      diags_.error(d.loc, "unknown format '" + r.format + "' for resource '" + r.name + "' (expected one of: " + list + ")");
      return;
    }
    if (r.format == "depth" && r.kind != ResourceKind::Input) {
      diags_.error(d.loc, "format 'depth' is only for kind=input resources ('" + r.name + "')");
      return;
    }
    if (a.count("formats") && !parseFormats(d, r, a["formats"])) return;
    if (a.count("format_when") && !parseFormatWhen(d, r, a["format_when"])) return;
    const std::string mips = a.count("mips") ? a["mips"] : "1";
    if (mips != "1" && mips != "auto") {
      diags_.error(d.loc, "mips of resource '" + r.name + "' must be 1 or auto, got '" + mips + "'");
      return;
    }
    r.fullMipChain = mips == "auto";
    if (r.fullMipChain && r.kind != ResourceKind::Image) {
      diags_.error(d.loc, "mips=auto is only for effect-owned images ('" + r.name + "')");
      return;
    }
    const std::string scale = a.count("scale") ? a["scale"] : "1";
    if (scale == "1") r.scaleDenominator = 1;
    else if (scale == "1/2") r.scaleDenominator = 2;
    else if (scale == "1/4") r.scaleDenominator = 4;
    else {
      diags_.error(d.loc, "scale of resource '" + r.name + "' must be 1, 1/2 or 1/4, got '" + scale + "'");
      return;
    }
    const std::string extent = a.count("extent") ? a["extent"] : (r.kind == ResourceKind::Input ? "input" : "ao");
    if (extent != "input" && extent != "ao") {
      diags_.error(d.loc, "extent of resource '" + r.name + "' must be input or ao, got '" + extent + "'");
      return;
    }
    if (r.kind == ResourceKind::Input && extent != "input") {
      diags_.error(d.loc, "input resource '" + r.name + "' has the input's extent by definition");
      return;
    }
    r.inputExtent = extent == "input";
    if (a.count("divide_by") && !parseDivideBy(d, r, a["divide_by"])) return;
    if (a.count("history")) {
      const std::string h = a["history"];
      std::string why;
      if (h != "true" && h != "false") why = "must be true or false, got '" + h + "'";
      else if (h == "true" && (r.kind != ResourceKind::Image || r.fullMipChain))
        why = "is only for single-level kind=image resources (kept across frames)";
      if (!why.empty()) {
        diags_.error(d.loc, "history of resource '" + r.name + "' " + why);
        return;
      }
      r.history = h == "true";
    }
    if (a.count("when")) {
      r.whenVariant = findVariant(a["when"]);
      if (r.whenVariant < 0) {
        diags_.error(d.loc, "resource '" + r.name + "' depends on unknown variant '" + a["when"] + "'");
        return;
      }
    }
    effect_.resources.push_back(r);
  }

  // formats=[F,...]: the formats a kind=output resource may have (its format= among them; a
  // variant with select=output:NAME picks one per plan), or the texel formats a colour kind=input
  // accepts (the backends refuse any other, naming these).
  bool parseFormats(const Directive& d, Resource& r, const std::string& list) {
    std::string why;
    if (r.kind == ResourceKind::Image) why = "is only for kind=input and kind=output resources";
    else if (r.format == "depth") why = "is not for a depth input (the backends accept their depth formats)";
    else if (list.size() < 2 || list.front() != '[' || list.back() != ']') why = "must be a list [F,...]";
    else
      for (const auto& f : splitList(list.substr(1, list.size() - 2))) {
        if (!isColourFormat(f)) why = "names '" + f + "', which is not a colour format";
        else if (std::find(r.formats.begin(), r.formats.end(), f) != r.formats.end()) why = "lists '" + f + "' twice";
        r.formats.push_back(f);
      }
    if (why.empty() && std::find(r.formats.begin(), r.formats.end(), r.format) == r.formats.end())
      why = "does not list its format= '" + r.format + "'";
    if (!why.empty()) {
      diags_.error(d.loc, "formats= of resource '" + r.name + "' " + why);
      return false;
    }
    return true;
  }

  // format_when=VARIANT:F: an effect-owned image that has format F where the variant is non-zero
  // (the rg16f intermediates); F holds as many channels as format=.
  bool parseFormatWhen(const Directive& d, Resource& r, const std::string& text) {
    const auto colon = text.find(':');
    const std::string variant = text.substr(0, colon);
    const std::string f = colon == std::string::npos ? "" : text.substr(colon + 1);
    std::string why;
    if (r.kind != ResourceKind::Image) why = "is only for kind=image resources";
    else if (colon == std::string::npos || variant.empty() || f.empty()) why = "must be VARIANT:FORMAT";
    else if (findVariant(variant) < 0) why = "names unknown variant '" + variant + "'";
    else if (!isColourFormat(f)) why = "names '" + f + "', which is not a colour format";
    else if (f == r.format) why = "names the resource's own format '" + f + "'";
    else if (formatChannels(f) != formatChannels(r.format))
      why = "names '" + f + "', which holds another number of channels than '" + r.format + "'";
    if (!why.empty()) {
      diags_.error(d.loc, "format_when= of resource '" + r.name + "' " + why);
      return false;
    }
    r.formatWhenVariant = findVariant(variant);
    r.formatWhen = f;
    return true;
  }

  // divide_by=SETTING: an effect-owned image of the AO extent whose extent is that over the value
  // of an int setting declared earlier, rounded up (the reduced-resolution AO images).
  bool parseDivideBy(const Directive& d, Resource& r, const std::string& name) {
    int found = -1;
    for (size_t i = 0; i < effect_.settings.size(); ++i)
      if (effect_.settings[i].name == name) found = static_cast<int>(i);
    std::string why;
    if (found < 0) why = "names setting '" + name + "', which is not declared before it";
    else if (effect_.settings[found].type != ScalarType::Int || effect_.settings[found].minValue < 1)
      why = "takes an int setting whose values are at least 1, not '" + name + "'";
    else if (r.kind != ResourceKind::Image || r.inputExtent || r.scaleDenominator != 1 || r.fullMipChain)
      why = "is only for single-level kind=image resources of the AO extent without scale=";
    if (!why.empty()) {
      diags_.error(d.loc, "divide_by of resource '" + r.name + "' " + why);
      return false;
    }
    r.divideBy = found;
    return true;
  }

  void parseBlock(const Directive& d, size_t next) {
    attrs(d, {});
    if (d.words.size() != 1 || !isIdentifier(d.words[0])) {
      diags_.error(d.loc, "expected '#pragma sao block NAME'");
      return;
    }
    if (effect_.block) {
      diags_.error(d.loc, "second parameter block: an effect has exactly one");
      return;
    }
    effect_.block = parseParamBlock(d.words[0], d.loc, src_.lines, next, diags_);
  }

  Pass* parsePass(const Directive& d) {
    attrs(d, {"entry", "local", "texels", "reads", "writes", "variants", "per", "levels", "skip_when", "alias_when"});
    Pass p;
    p.loc = d.loc;
    p.doc = d.doc;
    if (d.words.size() != 1) {
      diags_.error(d.loc, "expected '#pragma sao pass NAME entry=FUNC local=XxY reads=... writes=...'");
      p.name = "?";
    } else {
      p.name = d.words[0];
      nameIsNew(d, "pass", p.name);
    }
    effect_.passes.push_back(p);
    pendingPasses_.emplace_back(effect_.passes.size() - 1, d);
    return &effect_.passes.back();
  }

  std::vector<int> resolveList(const Pass& p, const Directive& d, const std::string& key, const std::string& verb) {
    std::vector<int> out;
    for (const auto& [k, v] : d.attrs) {
      if (k != key) continue;
      for (const auto& name : splitList(v)) {
        const int r = findResource(name);
        if (r < 0) {
          diags_.error(d.loc, "pass '" + p.name + "' " + verb + " undeclared resource '" + name + "'");
          continue;
        }
        if (std::find(out.begin(), out.end(), r) != out.end()) {
          diags_.error(d.loc, "pass '" + p.name + "' lists resource '" + name + "' twice in " + key +
                                  "= (duplicate binding)");
          continue;
        }
        out.push_back(r);
      }
    }
    return out;
  }

  void resolvePass(Pass& p, const Directive& d) {
    std::map<std::string, std::string> a;
    for (const auto& [k, v] : d.attrs) a[k] = v;
    if (!a.count("entry") || !isIdentifier(a["entry"])) {
      diags_.error(d.loc, "pass '" + p.name + "' needs entry=FUNCTION");
    } else {
      p.entry = a["entry"];
    }
    if (a.count("local")) {
      static const std::regex localRe("^([0-9]{1,4})x([0-9]{1,4})$");
      std::smatch m;
      if (!std::regex_match(a["local"], m, localRe) || std::stoi(m[1]) < 1 || std::stoi(m[2]) < 1 ||
          std::stoi(m[1]) * std::stoi(m[2]) > 1024) {
        diags_.error(d.loc, "local size of pass '" + p.name + "' must be XxY with 1 <= X*Y <= 1024, got '" + a["local"] + "'");
      } else {
        p.localX = std::stoi(m[1]);
        p.localY = std::stoi(m[2]);
      }
    }
    if (a.count("texels")) {
      static const std::regex texelsRe("^([1-4])x([1-4])$");
      std::smatch m;
      if (!std::regex_match(a["texels"], m, texelsRe)) {
        diags_.error(d.loc, "texels= of pass '" + p.name + "' must be WxH with W and H in 1..4, got '" + a["texels"] + "'");
      } else {
        p.texelsX = std::stoi(m[1]);
        p.texelsY = std::stoi(m[2]);
      }
    }
    if (a.count("per"))  // one dispatch per level is gone: a chain is written in one, levels=A..B
      diags_.error(d.loc, "per= of pass '" + p.name + "' is no longer part of the format: write a chain's levels in one dispatch with levels=A..B");
    if (a.count("levels")) {
      static const std::regex levelsRe("^([0-9]{1,2})\\.\\.([0-9]{1,2})$");
      std::smatch m;
      if (!std::regex_match(a["levels"], m, levelsRe) || std::stoi(m[1]) > std::stoi(m[2]) || std::stoi(m[2]) > 15)
        diags_.error(d.loc, "levels= of pass '" + p.name + "' must be A..B with 0 <= A <= B <= 15, got '" + a["levels"] + "'");
      else {
        p.firstLevel = std::stoi(m[1]);
        p.levelSlots = std::stoi(m[2]) - p.firstLevel + 1;
      }
    }
    if (a.count("variants")) {
      for (const auto& name : splitList(a["variants"])) {
        const int v = findVariant(name);
        if (v < 0) diags_.error(d.loc, "pass '" + p.name + "' lists unknown variant '" + name + "'");
        else if (std::find(p.variants.begin(), p.variants.end(), v) == p.variants.end()) p.variants.push_back(v);
      }
      std::sort(p.variants.begin(), p.variants.end());
      std::size_t combinations = 1;
      for (int v : p.variants) combinations *= effect_.variants[v].values.size();
      if (combinations > kMaxPassVariants)
        diags_.error(d.loc, "pass '" + p.name + "' lists variants with " + std::to_string(combinations) +
                                " combinations, more than " + std::to_string(kMaxPassVariants) +
                                "; each one is compiled (GLSL and SPIR-V)");
    }
    p.reads = resolveList(p, d, "reads", "reads");
    p.writes = resolveList(p, d, "writes", "writes");
    if (p.writes.empty()) diags_.error(d.loc, "pass '" + p.name + "' writes nothing");
    for (int r : p.writes) {
      const Resource& res = effect_.resources[r];
      if (res.kind == ResourceKind::Input)
        diags_.error(d.loc, "pass '" + p.name + "' writes input resource '" + res.name + "'");
      if (p.levelSlots > 0 && !res.fullMipChain)
        diags_.error(d.loc, "pass '" + p.name + "' writes levels= of '" + res.name + "', which has no MIP chain");
      // A levels= pass reads the level below its first (A - 1) of a chain it writes; from level 0 there is none.
      if (p.levelSlots > 0 && p.firstLevel == 0 && std::find(p.reads.begin(), p.reads.end(), r) != p.reads.end())
        diags_.error(d.loc, "pass '" + p.name + "' reads '" + res.name + "' and writes its levels from 0 on: a levels=A..B pass that reads a chain it writes needs A >= 1 (it reads level A - 1)");
    }
    for (int r : p.reads) {
      if (effect_.resources[r].kind == ResourceKind::Output)
        diags_.error(d.loc, "pass '" + p.name + "' reads output resource '" + effect_.resources[r].name + "'");
    }
    for (const auto* list : {&p.reads, &p.writes})
      for (int r : *list) {
        const Resource& res = effect_.resources[r];
        if (res.whenVariant >= 0 &&
            std::find(p.variants.begin(), p.variants.end(), res.whenVariant) == p.variants.end())
          diags_.error(d.loc, "pass '" + p.name + "' uses '" + res.name + "', which exists only when " +
                                  effect_.variants[res.whenVariant].name + " != 0, but does not list that variant in variants=");
      }
    for (int r : p.reads)
      for (size_t v = 0; v < effect_.variants.size(); ++v)
        if (effect_.variants[v].select == VariantSelect::Multisampled && effect_.variants[v].selectIndex == r &&
            std::find(p.variants.begin(), p.variants.end(), int(v)) == p.variants.end())
          diags_.error(d.loc, "pass '" + p.name + "' reads '" + effect_.resources[r].name + "', whose sample-count variant " +
                                  effect_.variants[v].name + " it does not list in variants=");
    for (int r : p.writes) {
      const Resource& res = effect_.resources[r];
      if (res.formatWhenVariant >= 0 &&
          std::find(p.variants.begin(), p.variants.end(), res.formatWhenVariant) == p.variants.end())
        diags_.error(d.loc, "pass '" + p.name + "' writes '" + res.name + "', whose format variant " +
                                effect_.variants[res.formatWhenVariant].name + " it does not list in variants=");
      if (res.formats.empty()) continue;
      int selector = -1;
      for (size_t v = 0; v < effect_.variants.size(); ++v)
        if (effect_.variants[v].select == VariantSelect::Output && effect_.variants[v].selectIndex == r) selector = int(v);
      if (selector < 0)
        diags_.error(d.loc, "pass '" + p.name + "' writes '" + res.name + "', which lists formats=, but no variant has select=output:" + res.name);
      else if (std::find(p.variants.begin(), p.variants.end(), selector) == p.variants.end())
        diags_.error(d.loc, "pass '" + p.name + "' writes '" + res.name + "', whose format variant " +
                                effect_.variants[selector].name + " it does not list in variants=");
    }
    resolvePassRules(effect_, p, d.loc, a.count("skip_when") ? &a["skip_when"] : nullptr,
                     a.count("alias_when") ? &a["alias_when"] : nullptr, diags_);
  }

  // Bindings are assigned by the tool; an explicit one in effect code would collide.
  void checkExplicitBindings() {
    static const std::regex bindingRe(R"(\bbinding\s*=\s*([0-9]+))");
    const SourceLoc* blockLoc = effect_.block ? &effect_.block->loc : nullptr;
    auto check = [&](const std::vector<SourceLine>& lines) {
      for (const auto& l : lines) {
        std::smatch m;
        const std::string code = l.text.substr(0, l.text.find("//"));
        if (!std::regex_search(code, m, bindingRe)) continue;
        if (blockLoc && l.text.find("std140") != std::string::npos && code.find("uniform " + effect_.block->name) != std::string::npos)
          continue;
        diags_.error(l.loc, "explicit 'binding = " + m[1].str() +
                                "' in effect code: bindings are assigned by sao-shaderc (duplicate binding risk); "
                                "declare a '#pragma sao resource' and list it in the pass's reads=/writes=");
      }
    };
    check(effect_.commonCode);
    for (const auto& p : effect_.passes) check(p.code);
  }

  const LoadedSource& src_;
  Diagnostics& diags_;
  Effect effect_;
  bool sawEffect_ = false;
  bool sawEffectDirective_ = false;
  std::map<std::string, SourceLoc> names_;
  std::vector<Directive> pendingExcludes_;
  std::vector<std::pair<size_t, Directive>> pendingPasses_;
  struct PendingText {
    SourceLoc loc;
    std::string text;
  };
  std::vector<std::pair<size_t, PendingText>> pendingSelects_;  // (variant index, select=)
  std::vector<Directive> pendingPresets_;
  std::vector<Directive> pendingDerived_;
  std::vector<Directive> pendingSettingRules_;
};

}  // namespace

Effect parseEffect(const LoadedSource& source, Diagnostics& diags) { return Parser(source, diags).run(); }

}  // namespace sao::codegen
