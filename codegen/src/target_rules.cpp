#include "target_rules.h"

#include <algorithm>

#include "formats.h"
#include "text_values.h"

namespace sao::codegen {
namespace {

// "[a,b]" -> {a, b}; false when not bracketed.
bool bracketList(const std::string& text, std::vector<std::string>& out) {
  if (text.size() < 2 || text.front() != '[' || text.back() != ']') return false;
  out = splitList(text.substr(1, text.size() - 2));
  return true;
}

bool sameKind(const FormatFacts& a, const FormatFacts& b) { return a.unorm == b.unorm && a.colour && b.colour; }

}  // namespace

void parseTargetRule(Effect& e, const SourceLoc& loc, const std::vector<std::string>& words,
                     const std::vector<std::pair<std::string, std::string>>& attrs, const std::string& doc,
                     bool hasDoc, Diagnostics& diags) {
  const char* usage = "expected '#pragma sao target gles storage=[F:G,...] refuse=[F,...] \"why\"'";
  if (words.size() != 1 || words[0] != "gles") {
    diags.error(loc, std::string(usage) + " (gles is the one target with rules: HLSL stores every format)");
    return;
  }
  if (e.gles) {
    diags.error(loc, "a second 'target gles' rule (the first is at line " + std::to_string(e.gles->loc.line) + ")");
    return;
  }
  if (!hasDoc || doc.empty()) diags.error(loc, "target needs a \"why\"");
  TargetRule rule;
  rule.loc = loc;
  rule.target = words[0];
  rule.doc = doc;
  bool ok = true;
  auto colour = [&](const std::string& name, const std::string& where) {
    const auto f = findFormat(name);
    if (f && f->colour) return true;
    diags.error(loc, where + " names '" + name + "', which is not a colour format");
    return ok = false;
  };
  std::vector<std::string> seen;
  auto once = [&](const std::string& name) {
    if (std::find(seen.begin(), seen.end(), name) == seen.end()) return seen.push_back(name), true;
    diags.error(loc, "target gles names '" + name + "' twice");
    return ok = false;
  };
  for (const auto& [key, value] : attrs) {
    std::vector<std::string> items;
    if ((key != "storage" && key != "refuse") || !bracketList(value, items)) {
      diags.error(loc, key == "storage" || key == "refuse" ? key + "= must be a list [...]"
                                                         : "unknown attribute '" + key + "' for 'target'");
      ok = false;
      continue;
    }
    for (const std::string& item : items) {
      if (key == "refuse") {
        if (colour(item, "refuse=") && once(item)) rule.refused.push_back(item);
        continue;
      }
      const auto colon = item.find(':');
      if (colon == std::string::npos) {
        diags.error(loc, "storage= item '" + item + "' is not FROM:TO");
        ok = false;
        continue;
      }
      StorageSubstitute s{item.substr(0, colon), item.substr(colon + 1)};
      if (!colour(s.from, "storage=") || !colour(s.to, "storage=") || !once(s.from)) continue;
      const FormatFacts from = *findFormat(s.from), to = *findFormat(s.to);
      if (from.esStorage) {
        diags.error(loc, "storage= substitutes '" + s.from + "', which OpenGL ES 3.1 stores itself");
        ok = false;
      } else if (!to.esStorage) {
        diags.error(loc, "storage= gives '" + s.from + "' the format '" + s.to + "', which OpenGL ES 3.1 cannot store either");
        ok = false;
      } else if (to.channels < from.channels || !sameKind(from, to)) {
        diags.error(loc, "storage= gives '" + s.from + "' the format '" + s.to +
                             "', which does not hold its channels the same way (as many or more, float for float, unorm for unorm)");
        ok = false;
      } else {
        rule.storage.push_back(s);
      }
    }
  }
  if (ok) e.gles = rule;
}

std::optional<std::string> glesStorageFormat(const Effect& e, const std::string& format) {
  const auto facts = findFormat(format);
  if (facts && facts->esStorage) return format;
  if (!e.gles) return std::nullopt;
  for (const auto& s : e.gles->storage)
    if (s.from == format) return s.to;
  return std::nullopt;
}

void checkTargetRules(const Effect& e, Diagnostics& diags) {
  if (!e.gles) return;
  for (const auto& r : e.resources) {
    if (r.kind == ResourceKind::Input) continue;
    std::vector<std::string> stored = r.kind == ResourceKind::Output && !r.formats.empty() ? r.formats
                                                                                           : std::vector<std::string>{r.format};
    if (r.formatWhenVariant >= 0) stored.push_back(r.formatWhen);
    for (const auto& f : stored) {
      const bool refused = std::find(e.gles->refused.begin(), e.gles->refused.end(), f) != e.gles->refused.end();
      const bool stores = glesStorageFormat(e, f).has_value();
      if (refused && r.kind != ResourceKind::Output)
        diags.error(e.gles->loc, "target gles refuses '" + f + "', which the effect's own image '" + r.name +
                                     "' has: only a caller's output format may be refused (substitute it instead)");
      else if (refused && stores)
        diags.error(e.gles->loc, "target gles both refuses and stores '" + f + "'");
      else if (!refused && !stores)
        diags.error(e.gles->loc, "resource '" + r.name + "' stores '" + f +
                                     "', which OpenGL ES 3.1 cannot store: give it a storage= substitute or refuse= it");
    }
  }
}

}  // namespace sao::codegen
