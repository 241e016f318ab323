// The rules plan() applies at run time, declared on directives and checked here against the
// settings and resources: which setting or input selects a variant (`select=`), when a pass is
// skipped (`skip_when=`) or reads another resource in place of a skipped pass's output
// (`alias_when=`), and named presets of setting values (`preset`).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "diagnostics.h"
#include "effect_model.h"

namespace sao::codegen {

// `select=SETTING` or `select=input:RESOURCE` of variant `v` (settings and resources all parsed).
void resolveVariantSelect(const Effect& e, Variant& v, const SourceLoc& loc, const std::string& text,
                          Diagnostics& diags);

// `skip_when=` and `alias_when=` of pass `p` (null when absent), after its reads and variants.
void resolvePassRules(const Effect& e, Pass& p, const SourceLoc& loc, const std::string* skipWhen,
                      const std::string* aliasWhen, Diagnostics& diags);

// Across passes, in order, over every combination of the settings the conditions name: a skipped
// pass's output reaches later readers only through an alias, every alias stands in for a skipped
// writer from a resource written then, and every output has a writer that runs.
void checkPassRules(const Effect& e, Diagnostics& diags);

// `derived NAME when=TERM&&TERM... "doc"` (settings all parsed; before the passes' rules, which
// may name it).
void parseDerived(Effect& e, const SourceLoc& loc, const std::vector<std::string>& words,
                  const std::vector<std::pair<std::string, std::string>>& attrs, const std::string& doc, bool hasDoc,
                  Diagnostics& diags);

// `inert SETTING when=COND "why"`, or with `refusal` `refuse SETTING when=COND "why"` (settings and
// derived settings all parsed).
void parseSettingRule(Effect& e, bool refusal, const SourceLoc& loc, const std::vector<std::string>& words,
                      const std::vector<std::pair<std::string, std::string>>& attrs, const std::string& doc,
                      bool hasDoc, Diagnostics& diags);

// The name of setting index `i` of a condition (a setting, or a derived setting past them).
const std::string& conditionSettingName(const Effect& e, int i);

// `preset NAME SETTING=VALUE ... "summary"`.
void parsePreset(Effect& e, const SourceLoc& loc, const std::vector<std::string>& words,
                 const std::vector<std::pair<std::string, std::string>>& attrs, const std::string& doc,
                 bool hasDoc, Diagnostics& diags);

}  // namespace sao::codegen
