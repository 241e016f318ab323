#include "effect_rules.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>
#include <sstream>

#include "text_values.h"

namespace sao::codegen {
namespace {

int findSetting(const Effect& e, const std::string& name) {
  for (size_t i = 0; i < e.settings.size(); ++i)
    if (e.settings[i].name == name) return static_cast<int>(i);
  return -1;
}

int findResource(const Effect& e, const std::string& name) {
  for (size_t i = 0; i < e.resources.size(); ++i)
    if (e.resources[i].name == name) return static_cast<int>(i);
  return -1;
}

const char* typeName(ScalarType t) {
  return t == ScalarType::Float ? "float" : t == ScalarType::Int ? "int" : "bool";
}

std::string valueText(const Setting& s, double v) {
  if (s.type == ScalarType::Bool) return v != 0 ? "true" : "false";
  std::ostringstream o;
  o << v;
  return o.str();
}

std::string rangeText(const Setting& s) {
  if (!s.allowed.empty()) {
    std::string t;
    for (double v : s.allowed) t += (t.empty() ? "" : ",") + valueText(s, v);
    return "{" + t + "}";
  }
  return "[" + valueText(s, s.minValue) + "," + valueText(s, s.maxValue) + "]";
}

bool allowedValue(const Setting& s, double v) {
  if (v < s.minValue || v > s.maxValue) return false;
  return s.allowed.empty() || std::find(s.allowed.begin(), s.allowed.end(), v) != s.allowed.end();
}

bool conditionHolds(const SettingCondition& c, double v) {
  switch (c.op) {
    case CompareOp::Eq: return v == c.value;
    case CompareOp::Ne: return v != c.value;
    case CompareOp::Lt: return v < c.value;
    case CompareOp::Le: return v <= c.value;
    case CompareOp::Gt: return v > c.value;
    case CompareOp::Ge: return v >= c.value;
  }
  return false;
}

// The values an int or bool setting takes in the checks below: every value of its range, or of a very
// wide int range its ends and each literal it is compared with and its neighbours (where an answer can
// change).
std::vector<double> settingValues(const Setting& s, const std::vector<double>& literals) {
  if (!s.allowed.empty()) return s.allowed;
  if (s.maxValue - s.minValue <= 1024) {
    std::vector<double> all;
    for (double v = s.minValue; v <= s.maxValue; ++v) all.push_back(v);
    return all;
  }
  std::vector<double> some{s.minValue, s.maxValue};
  for (double l : literals)
    for (double v : {l - 1, l, l + 1})
      if (v >= s.minValue && v <= s.maxValue && std::find(some.begin(), some.end(), v) == some.end()) some.push_back(v);
  return some;
}

// The derived setting a condition's setting index names (past the settings), or null.
const DerivedSetting* derivedOf(const Effect& e, int setting) {
  return setting < static_cast<int>(e.settings.size()) ? nullptr
                                                        : &e.derived[static_cast<size_t>(setting) - e.settings.size()];
}

// The settings a condition names, through derived settings' terms (which may name earlier derived
// settings), with the literals each is compared with.
void collectSettings(const Effect& e, const SettingCondition& c, std::map<int, std::vector<double>>& out) {
  if (const DerivedSetting* d = derivedOf(e, c.setting)) {
    for (const auto& t : d->terms) collectSettings(e, t, out);
    return;
  }
  out[c.setting].push_back(c.value);
}

// One value per setting index (NaN: not involved).
using Assignment = std::vector<double>;

// Every combination of values of the settings the conditions involve (null ones ignored).
std::vector<Assignment> assignments(const Effect& e, const std::vector<const SettingCondition*>& conditions) {
  std::map<int, std::vector<double>> literals;
  for (const auto* c : conditions)
    if (c) collectSettings(e, *c, literals);
  std::vector<Assignment> out{Assignment(e.settings.size(), std::nan(""))};
  for (const auto& [setting, lits] : literals) {
    std::vector<Assignment> next;
    for (const auto& a : out)
      for (double v : settingValues(e.settings[static_cast<size_t>(setting)], lits)) {
        next.push_back(a);
        next.back()[static_cast<size_t>(setting)] = v;
      }
    out = std::move(next);
  }
  return out;
}

// Whether condition c (null: never) holds under assignment a.
bool holdsAt(const Effect& e, const std::optional<SettingCondition>& c, const Assignment& a) {
  if (!c) return false;
  const DerivedSetting* d = derivedOf(e, c->setting);
  if (!d) return conditionHolds(*c, a[static_cast<size_t>(c->setting)]);
  bool all = true;
  for (const auto& t : d->terms) all = all && holdsAt(e, t, a);
  return conditionHolds(*c, all ? 1 : 0);
}

// A literal of the setting's type inside its range; `owner` starts each message.
bool parseSettingValue(const Setting& s, const std::string& text, const SourceLoc& loc, const std::string& owner,
                       double& out, Diagnostics& diags) {
  bool ok = false;
  if (s.type == ScalarType::Bool) {
    ok = text == "true" || text == "false";
    out = text == "true" ? 1 : 0;
  } else if (s.type == ScalarType::Int) {
    int v = 0;
    ok = parseInt(text, v);
    out = v;
  } else {
    ok = parseNumber(text, out);
  }
  if (!ok) {
    diags.error(loc, owner + ": '" + text + "' is not a value of " + typeName(s.type) + " setting '" + s.name + "'" +
                         (s.type == ScalarType::Bool ? " (true or false)" : ""));
    return false;
  }
  if (!allowedValue(s, out)) {
    diags.error(loc, owner + ": " + text + (s.allowed.empty() ? " is outside the range " : " is not one of the values ") +
                         rangeText(s) + " of setting '" + s.name + "'");
    return false;
  }
  return true;
}

// `allowFloat`: a float setting may be compared too (inert rules; the pass rules enumerate their
// settings' values, which a float range does not have).
bool parseCondition(const Effect& e, const std::string& text, const SourceLoc& loc, const std::string& owner,
                    SettingCondition& out, Diagnostics& diags, bool allowFloat = false) {
  static const std::regex re(R"(^([A-Za-z_][A-Za-z0-9_]*)(==|!=|<=|>=|<|>)([^=<>!]+)$)");
  std::smatch m;
  if (!std::regex_match(text, m, re)) {
    diags.error(loc, owner + " must be SETTING==VALUE (or !=, <, <=, >, >=), got '" + text + "'");
    return false;
  }
  out.text = text;
  const std::string op = m[2];
  out.op = op == "==" ? CompareOp::Eq : op == "!=" ? CompareOp::Ne : op == "<" ? CompareOp::Lt
         : op == "<=" ? CompareOp::Le : op == ">" ? CompareOp::Gt : CompareOp::Ge;
  out.setting = findSetting(e, m[1]);
  if (out.setting < 0) {
    for (size_t j = 0; j < e.derived.size(); ++j)
      if (e.derived[j].name == m[1]) out.setting = static_cast<int>(e.settings.size() + j);
    if (out.setting < 0) {
      diags.error(loc, owner + " names unknown setting '" + m[1].str() + "'");
      return false;
    }
    // A derived setting: a bool (true when all its terms hold).
    const std::string value = m[3];
    if (out.op != CompareOp::Eq && out.op != CompareOp::Ne) {
      diags.error(loc, owner + " orders derived setting '" + m[1].str() + "': use == or !=");
      return false;
    }
    if (value != "true" && value != "false") {
      diags.error(loc, owner + ": '" + value + "' is not a value of derived setting '" + m[1].str() +
                           "' (true or false)");
      return false;
    }
    out.value = value == "true" ? 1 : 0;
    return true;
  }
  const Setting& s = e.settings[out.setting];
  if (s.type == ScalarType::Float && !allowFloat) {
    diags.error(loc, owner + " compares float setting '" + s.name + "': a condition takes an int or bool setting");
    return false;
  }
  if (s.type == ScalarType::Bool && out.op != CompareOp::Eq && out.op != CompareOp::Ne) {
    diags.error(loc, owner + " orders bool setting '" + s.name + "': use == or !=");
    return false;
  }
  return parseSettingValue(s, m[3], loc, owner, out.value, diags);
}

bool sameExtent(const Resource& a, const Resource& b) {
  return a.inputExtent == b.inputExtent && a.scaleDenominator == b.scaleDenominator && a.divideBy == b.divideBy;
}

bool writes(const Pass& p, int r) { return std::find(p.writes.begin(), p.writes.end(), r) != p.writes.end(); }

// Whether a pass before pass `before` that writes resource r runs under assignment a.
bool writtenBefore(const Effect& e, size_t before, int r, const Assignment& a) {
  for (size_t j = 0; j < before; ++j)
    if (writes(e.passes[j], r) && !holdsAt(e, e.passes[j].skipWhen, a)) return true;
  return false;
}

const ResourceAlias* aliasOf(const std::vector<ResourceAlias>& aliases, int declared) {
  for (const auto& a : aliases)
    if (a.declared == declared) return &a;
  return nullptr;
}

}  // namespace

void resolveVariantSelect(const Effect& e, Variant& v, const SourceLoc& loc, const std::string& text,
                          Diagnostics& diags) {
  const std::string prefix = "input:";
  const std::string outputPrefix = "output:";
  const std::string multisampledPrefix = "multisampled:";
  if (text.rfind(multisampledPrefix, 0) == 0) {
    // 1 when the input has several samples per texel: its sampler becomes sampler2DMS.
    const std::string name = text.substr(multisampledPrefix.size());
    const int r = findResource(e, name);
    if (r < 0 || e.resources[r].kind != ResourceKind::Input || e.resources[r].whenVariant >= 0) {
      diags.error(loc, "variant '" + v.name + "' is selected by '" + text +
                           "', which names no kind=input resource that always exists");
      return;
    }
    for (const Variant& other : e.variants)
      if (other.select == VariantSelect::Multisampled && other.selectIndex == r && other.name != v.name) {
        diags.error(loc, "variant '" + v.name + "' is selected by '" + text + "', which variant '" + other.name +
                             "' already selects");
        return;
      }
    if (v.values != std::vector<int>{0, 1} || v.defaultValue != 0) {
      diags.error(loc, "variant '" + v.name + "' is selected by '" + text +
                           "': its values must be [0,1] and its default 0 (single-sample)");
      return;
    }
    v.select = VariantSelect::Multisampled;
    v.selectIndex = r;
    return;
  }
  if (text.rfind(outputPrefix, 0) == 0) {
    // The index of the output image's format in the resource's formats=: values 0..n-1.
    const std::string name = text.substr(outputPrefix.size());
    const int r = findResource(e, name);
    if (r < 0 || e.resources[r].kind != ResourceKind::Output || e.resources[r].formats.empty()) {
      diags.error(loc, "variant '" + v.name + "' is selected by '" + text +
                           "', which names no kind=output resource with formats=");
      return;
    }
    const size_t n = e.resources[r].formats.size();
    bool ok = v.values.size() == n;
    for (size_t i = 0; ok && i < n; ++i) ok = v.values[i] == static_cast<int>(i);
    const auto& formats = e.resources[r].formats;
    const int defaultIndex =
        static_cast<int>(std::find(formats.begin(), formats.end(), e.resources[r].format) - formats.begin());
    if (!ok || v.defaultValue != defaultIndex) {
      diags.error(loc, "variant '" + v.name + "' is selected by '" + text + "': its values must be 0.." +
                           std::to_string(n - 1) + " (one per format of '" + name + "') and its default " +
                           std::to_string(defaultIndex) + " (the resource's format=)");
      return;
    }
    v.select = VariantSelect::Output;
    v.selectIndex = r;
    return;
  }
  if (text.rfind(prefix, 0) == 0) {
    const std::string name = text.substr(prefix.size());
    const int r = findResource(e, name);
    if (r < 0) {
      diags.error(loc, "variant '" + v.name + "' is selected by undeclared resource '" + name + "'");
      return;
    }
    const Resource& res = e.resources[r];
    if (res.kind != ResourceKind::Input) {
      diags.error(loc, "variant '" + v.name + "' is selected by resource '" + name +
                           "', which is not kind=input (select=input: takes an input the user supplies)");
      return;
    }
    if (res.whenVariant >= 0 && e.variants[res.whenVariant].name != v.name) {
      diags.error(loc, "variant '" + v.name + "' is selected by input '" + name + "', which exists only when " +
                           e.variants[res.whenVariant].name + " != 0");
      return;
    }
    v.select = VariantSelect::Input;
    v.selectIndex = r;
  } else {
    const int s = findSetting(e, text);
    if (s < 0) {
      diags.error(loc, "variant '" + v.name + "' is selected by unknown setting '" + text + "'");
      return;
    }
    // A bool setting, or an int one whose only values are 0 and 1: either way the variant's value
    // is the setting's (plan(): value != 0).
    const Setting& st = e.settings[s];
    const bool intZeroOne = st.type == ScalarType::Int && st.allowed == std::vector<double>{0.0, 1.0};
    if (st.type != ScalarType::Bool && !intZeroOne) {
      diags.error(loc, "variant '" + v.name + "' is selected by " + typeName(st.type) + " setting '" + text +
                           "': select= takes a bool setting, an int setting with values=[0,1], or input:RESOURCE");
      return;
    }
    v.select = VariantSelect::Setting;
    v.selectIndex = s;
  }
  const auto has = [&](int x) { return std::find(v.values.begin(), v.values.end(), x) != v.values.end(); };
  if (!has(0) || !has(1)) {
    diags.error(loc, "variant '" + v.name + "' is selected by '" + text +
                         "', which gives 0 or 1, but its values do not include both");
    v.select = VariantSelect::Default;
    v.selectIndex = -1;
  }
}

const std::string& conditionSettingName(const Effect& e, int i) {
  const DerivedSetting* d = derivedOf(e, i);
  return d ? d->name : e.settings[static_cast<size_t>(i)].name;
}

void resolvePassRules(const Effect& e, Pass& p, const SourceLoc& loc, const std::string* skipWhen,
                      const std::string* aliasWhen, Diagnostics& diags) {
  if (skipWhen) {
    SettingCondition c;
    if (parseCondition(e, *skipWhen, loc, "skip_when of pass '" + p.name + "'", c, diags)) p.skipWhen = c;
  }
  if (!aliasWhen) return;
  const std::string owner = "alias_when of pass '" + p.name + "'";
  const size_t colon = aliasWhen->find(':');
  if (colon == std::string::npos) {
    diags.error(loc, owner + " must be CONDITION:RESOURCE=RESOURCE[,...], got '" + *aliasWhen + "'");
    return;
  }
  SettingCondition c;
  if (!parseCondition(e, aliasWhen->substr(0, colon), loc, owner, c, diags)) return;
  std::vector<ResourceAlias> aliases;
  for (const auto& pair : splitList(aliasWhen->substr(colon + 1))) {
    const auto names = splitList(pair, '=');
    if (names.size() != 2) {
      diags.error(loc, owner + ": '" + pair + "' is not DECLARED=SERVING");
      return;
    }
    ResourceAlias a{findResource(e, names[0]), findResource(e, names[1])};
    for (int i = 0; i < 2; ++i)
      if ((i ? a.serving : a.declared) < 0) {
        diags.error(loc, owner + " names undeclared resource '" + names[i] + "'");
        return;
      }
    const Resource& from = e.resources[a.declared];
    const Resource& to = e.resources[a.serving];
    std::string why;
    if (std::find(p.reads.begin(), p.reads.end(), a.declared) == p.reads.end())
      why = "replaces '" + from.name + "', which the pass does not read";
    else if (aliasOf(aliases, a.declared))
      why = "replaces '" + from.name + "' twice";
    else if (a.serving == a.declared)
      why = "serves '" + from.name + "' by itself";
    else if (to.kind == ResourceKind::Output)
      why = "serves '" + from.name + "' from output resource '" + to.name + "' (passes do not read outputs)";
    else if (to.format != from.format)
      why = "serves '" + from.name + "' (" + from.format + ") from '" + to.name + "' (" + to.format + "): the formats differ";
    else if (to.formatWhenVariant != from.formatWhenVariant || to.formatWhen != from.formatWhen)
      why = "serves '" + from.name + "' from '" + to.name + "', whose format_when= differ";
    else if (!sameExtent(from, to))
      why = "serves '" + from.name + "' from '" + to.name + "': their extents differ";
    else if (to.whenVariant >= 0 &&
             std::find(p.variants.begin(), p.variants.end(), to.whenVariant) == p.variants.end())
      why = "serves '" + from.name + "' from '" + to.name + "', which exists only when " +
            e.variants[to.whenVariant].name + " != 0, but the pass does not list that variant in variants=";
    if (!why.empty()) {
      diags.error(loc, owner + " " + why);
      return;
    }
    aliases.push_back(a);
  }
  p.aliasWhen = c;
  p.aliases = aliases;
}

void checkPassRules(const Effect& e, Diagnostics& diags) {
  // Every check below runs over every combination of the values of the settings that the
  // conditions involved name (derived settings through their terms), so conditions on different
  // settings combine (e.g. the output written by one of three passes on two settings).
  for (size_t i = 0; i < e.passes.size(); ++i) {
    const Pass& p = e.passes[i];
    // An output's writer may be skipped only where another writer of it runs (e.g. the full- and
    // reduced-resolution ends of the effect, skipped on complementary values of one setting).
    if (p.skipWhen)
      for (int r : p.writes)
        if (e.resources[r].kind == ResourceKind::Output) {
          std::vector<const SettingCondition*> conditions{&*p.skipWhen};
          for (const Pass& q : e.passes)
            if (&q != &p && writes(q, r) && q.skipWhen) conditions.push_back(&*q.skipWhen);
          for (const auto& a : assignments(e, conditions)) {
            if (!holdsAt(e, p.skipWhen, a)) continue;
            bool covered = false;
            for (const Pass& q : e.passes)
              if (&q != &p && writes(q, r) && !holdsAt(e, q.skipWhen, a)) covered = true;
            if (!covered) {
              diags.error(p.loc, "pass '" + p.name + "' writes output '" + e.resources[r].name + "' but has skip_when=" +
                                     p.skipWhen->text + ": the output would be left unwritten");
              break;
            }
          }
        }
    // Each alias stands in for an earlier writer skipped whenever the alias applies (and the pass
    // runs), from a resource an earlier pass writes then (or an input).
    for (const auto& al : p.aliases) {
      std::vector<const SettingCondition*> conditions{&*p.aliasWhen};
      if (p.skipWhen) conditions.push_back(&*p.skipWhen);
      for (size_t j = 0; j < i; ++j)
        if (e.passes[j].skipWhen) conditions.push_back(&*e.passes[j].skipWhen);
      const auto all = assignments(e, conditions);
      const auto applies = [&](const Assignment& a) { return holdsAt(e, p.aliasWhen, a) && !holdsAt(e, p.skipWhen, a); };
      bool skippedWriter = false, servingWritten = true;
      for (size_t j = 0; j < i; ++j) {
        const Pass& w = e.passes[j];
        if (writes(w, al.declared) && w.skipWhen &&
            std::all_of(all.begin(), all.end(), [&](const Assignment& a) { return !applies(a) || holdsAt(e, w.skipWhen, a); }))
          skippedWriter = true;
      }
      if (e.resources[al.serving].kind != ResourceKind::Input)
        for (const auto& a : all)
          if (applies(a) && !writtenBefore(e, i, al.serving, a)) servingWritten = false;
      if (!skippedWriter)
        diags.error(p.loc, "alias_when of pass '" + p.name + "' serves '" + e.resources[al.declared].name + "' when " +
                               p.aliasWhen->text + ", but no earlier pass that writes it is skipped then");
      else if (!servingWritten)
        diags.error(p.loc, "alias_when of pass '" + p.name + "' serves '" + e.resources[al.declared].name + "' from '" +
                               e.resources[al.serving].name + "', which no earlier pass writes when " +
                               p.aliasWhen->text);
    }
    // A history is read as the previous frame left it: the pass that reads it must write this
    // frame's, or the next frame would read a stale image.
    for (int r : p.reads)
      if (e.resources[r].history && !writes(p, r))
        diags.error(p.loc, "pass '" + p.name + "' reads history resource '" + e.resources[r].name +
                               "' but does not write it: the pass that reads a history writes this frame's");
    for (const auto& al : p.aliases)
      if (e.resources[al.declared].history || e.resources[al.serving].history)
        diags.error(p.loc, "alias_when of pass '" + p.name + "' names history resource '" +
                               e.resources[e.resources[al.declared].history ? al.declared : al.serving].name +
                               "': a history is never served by or for another image");
    // A read whose earlier writers can all be skipped while the pass runs needs an alias then.
    for (int r : p.reads) {
      const Pass* last = nullptr;
      bool always = false;
      std::vector<const SettingCondition*> conditions;
      if (p.skipWhen) conditions.push_back(&*p.skipWhen);
      if (p.aliasWhen) conditions.push_back(&*p.aliasWhen);
      for (size_t j = 0; j < i; ++j) {
        if (!writes(e.passes[j], r)) continue;
        if (!e.passes[j].skipWhen) always = true;
        else conditions.push_back(&*e.passes[j].skipWhen);
        last = &e.passes[j];
      }
      if (!last || always) continue;
      for (const auto& a : assignments(e, conditions)) {
        if (holdsAt(e, p.skipWhen, a)) continue;
        if (aliasOf(p.aliases, r) && holdsAt(e, p.aliasWhen, a)) continue;
        if (writtenBefore(e, i, r, a)) continue;
        diags.error(p.loc, "pass '" + p.name + "' reads '" + e.resources[r].name + "', which pass '" + last->name +
                               "' does not write when " + last->skipWhen->text + "; add alias_when=" +
                               last->skipWhen->text + ":" + e.resources[r].name + "=RESOURCE to pass '" + p.name + "'");
        break;
      }
    }
  }
}

void parseDerived(Effect& e, const SourceLoc& loc, const std::vector<std::string>& words,
                  const std::vector<std::pair<std::string, std::string>>& attrs, const std::string& doc, bool hasDoc,
                  Diagnostics& diags) {
  if (words.size() != 1 || attrs.size() != 1 || attrs[0].first != "when") {
    diags.error(loc, "expected '#pragma sao derived NAME when=SETTING==VALUE[&&SETTING==VALUE...] \"doc\"'");
    return;
  }
  DerivedSetting d;
  d.loc = loc;
  d.name = words[0];
  d.doc = doc;
  if (!hasDoc || doc.empty()) {
    diags.error(loc, "derived setting '" + d.name + "' has no doc string");
    return;
  }
  const std::string owner = "when= of derived setting '" + d.name + "'";
  const std::string& text = attrs[0].second;
  for (size_t from = 0;;) {
    const size_t amp = text.find("&&", from);
    SettingCondition c;
    if (!parseCondition(e, text.substr(from, amp == std::string::npos ? std::string::npos : amp - from), loc, owner, c,
                        diags))
      return;
    d.terms.push_back(c);
    if (amp == std::string::npos) break;
    from = amp + 2;
  }
  e.derived.push_back(d);
}

namespace {

const char* opText(CompareOp op) {
  switch (op) {
    case CompareOp::Eq: return "=";
    case CompareOp::Ne: return "!=";
    case CompareOp::Lt: return "<";
    case CompareOp::Le: return "<=";
    case CompareOp::Gt: return ">";
    case CompareOp::Ge: return ">=";
  }
  return "?";
}

// "a, b and c" / "a, b or c".
std::string joined(const std::vector<std::string>& parts, const std::string& last) {
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i)
    out += (i == 0 ? "" : i + 1 == parts.size() ? " " + last + " " : ", ") + parts[i];
  return out;
}

// Whether a condition on a derived setting holds when all its terms do (==true, !=false).
bool holdsWhenAllTerms(const SettingCondition& c) { return (c.op == CompareOp::Eq) == (c.value != 0); }

// Condition c in words, a derived setting's terms spelled out ("blur_radius = 0, ... and temporal = false").
std::string conditionWords(const Effect& e, const SettingCondition& c, bool negate);

std::string termsWords(const Effect& e, const DerivedSetting& d, bool negate) {
  std::vector<std::string> parts;
  for (const auto& t : d.terms) parts.push_back(conditionWords(e, t, negate));
  return joined(parts, negate ? "or" : "and");
}

// `negate`: the condition that makes c false, as the fix of a message says it ("fade_end > 0").
std::string conditionWords(const Effect& e, const SettingCondition& c, bool negate) {
  if (const DerivedSetting* d = derivedOf(e, c.setting)) {
    // All terms hold / some term fails; the other way round for ==false.
    const bool all = holdsWhenAllTerms(c) != negate;
    return all ? termsWords(e, *d, false) : termsWords(e, *d, true);
  }
  const Setting& s = e.settings[static_cast<size_t>(c.setting)];
  if (!negate) return s.name + " " + opText(c.op) + " " + valueText(s, c.value);
  if (s.type == ScalarType::Bool) {
    const bool holdsWhenTrue = (c.op == CompareOp::Eq) == (c.value != 0);
    return s.name + " = " + (holdsWhenTrue ? "false" : "true");
  }
  CompareOp op = CompareOp::Ne;
  switch (c.op) {
    case CompareOp::Eq:  // the only way out of a range's end is inwards
      op = c.value == s.minValue ? CompareOp::Gt : c.value == s.maxValue ? CompareOp::Lt : CompareOp::Ne;
      break;
    case CompareOp::Ne: op = CompareOp::Eq; break;
    case CompareOp::Lt: op = CompareOp::Ge; break;
    case CompareOp::Le: op = CompareOp::Gt; break;
    case CompareOp::Gt: op = CompareOp::Le; break;
    case CompareOp::Ge: op = CompareOp::Lt; break;
  }
  return s.name + " " + opText(op) + " " + valueText(s, c.value);
}

// Whether condition c holds for some / every value of the settings it names: for int and bool
// settings every value (settingValues), for a float one its range's ends and the literal (a
// comparison changes its answer only there).
void conditionReach(const Effect& e, const SettingCondition& c, bool& some, bool& every) {
  some = false;
  every = true;
  const DerivedSetting* d = derivedOf(e, c.setting);
  if (!d && e.settings[static_cast<size_t>(c.setting)].type == ScalarType::Float) {
    const Setting& s = e.settings[static_cast<size_t>(c.setting)];
    for (double v : {s.minValue, s.maxValue, c.value}) {
      const bool h = conditionHolds(c, v);
      some = some || h;
      every = every && h;
    }
    return;
  }
  for (const auto& a : assignments(e, {&c})) {
    const bool h = holdsAt(e, c, a);
    some = some || h;
    every = every && h;
  }
}

}  // namespace

void parseSettingRule(Effect& e, bool refusal, const SourceLoc& loc, const std::vector<std::string>& words,
                      const std::vector<std::pair<std::string, std::string>>& attrs, const std::string& doc,
                      bool hasDoc, Diagnostics& diags) {
  const std::string kind = refusal ? "refuse" : "inert";
  if (words.size() != 1 || attrs.size() != 1 || attrs[0].first != "when") {
    diags.error(loc, "expected '#pragma sao " + kind + " SETTING when=SETTING==VALUE \"why\"'");
    return;
  }
  const std::string& name = words[0];
  InertRule r;
  r.loc = loc;
  r.doc = doc;
  r.setting = findSetting(e, name);
  if (r.setting < 0) {
    const bool derived = std::any_of(e.derived.begin(), e.derived.end(), [&](const DerivedSetting& d) { return d.name == name; });
    diags.error(loc, derived ? kind + " names derived setting '" + name + "', which nobody sets (plan() computes it)"
                             : kind + " names unknown setting '" + name + "'");
    return;
  }
  const std::string owner = "when= of " + std::string(refusal ? "refused" : "inert") + " setting '" + name + "'";
  if (!hasDoc || doc.empty()) {
    diags.error(loc, std::string(refusal ? "refused" : "inert") + " setting '" + name +
                         "' has no \"why\" (the reason messages give)");
    return;
  }
  if (!parseCondition(e, attrs[0].second, loc, owner, r.when, diags, /*allowFloat=*/true)) return;
  std::map<int, std::vector<double>> named;
  collectSettings(e, r.when, named);
  if (named.count(r.setting)) {
    diags.error(loc, owner + " names '" + name + "' itself: " +
                         (refusal ? "a rule on a setting's own value is its range's job"
                                  : "a setting's own value cannot make it have no effect"));
    return;
  }
  bool some = false, every = false;
  conditionReach(e, r.when, some, every);
  if (!some || every) {
    const std::string of = " of " + conditionSettingName(e, r.when.setting);
    const std::string never = refusal ? "' is always refused" : "' never has an effect";
    diags.error(loc, owner + (some ? " holds for every value" + of + ", so '" + name + never + ": drop the setting or the rule"
                                   : " holds for no value" + of + ", so the rule never applies: drop it"));
    return;
  }
  std::vector<InertRule>& rules = refusal ? e.refusals : e.inert;
  for (const auto& other : rules)
    if (other.setting == r.setting && other.when.text == r.when.text) {
      diags.error(loc, "duplicate " + kind + " rule for '" + name + "' (first declared at line " +
                           std::to_string(other.loc.line) + ")");
      return;
    }
  r.whenText = conditionWords(e, r.when, false);
  r.fixText = conditionWords(e, r.when, true);
  rules.push_back(r);
}

void parsePreset(Effect& e, const SourceLoc& loc, const std::vector<std::string>& words,
                 const std::vector<std::pair<std::string, std::string>>& attrs, const std::string& doc,
                 bool hasDoc, Diagnostics& diags) {
  static const std::regex nameRe("^[a-z][a-z0-9_]*$");
  if (words.size() != 1 || !std::regex_match(words[0], nameRe)) {
    diags.error(loc, "expected '#pragma sao preset NAME SETTING=VALUE ... \"summary\"' with NAME in lower case "
                     "(the C++ enumerator upper-cases its first letter)");
    return;
  }
  Preset p;
  p.loc = loc;
  p.name = words[0];
  p.doc = doc;
  for (const auto& other : e.presets)
    if (other.name == p.name) {
      diags.error(loc, "duplicate preset '" + p.name + "' (first declared at line " + std::to_string(other.loc.line) + ")");
      return;
    }
  if (!hasDoc || doc.empty()) {
    diags.error(loc, "preset '" + p.name + "' has no \"summary\"");
    return;
  }
  const std::string owner = "preset '" + p.name + "'";
  for (const auto& [name, text] : attrs) {
    const int s = findSetting(e, name);
    if (s < 0) {
      diags.error(loc, owner + " sets unknown setting '" + name + "'");
      return;
    }
    for (const auto& [other, value] : p.values)
      if (other == s) {
        diags.error(loc, owner + " sets '" + name + "' twice");
        return;
      }
    double v = 0;
    if (!parseSettingValue(e.settings[s], text, loc, owner, v, diags)) return;
    p.values.emplace_back(s, v);
  }
  e.presets.push_back(p);
}

}  // namespace sao::codegen
