// `#pragma sao target gles ...`: the effect's storage formats on OpenGL ES 3.1 (effect_model.h,
// TargetRule), parsed, checked against every format the effect stores, and asked per format.
#pragma once
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "diagnostics.h"
#include "effect_model.h"

namespace sao::codegen {

void parseTargetRule(Effect& e, const SourceLoc& loc, const std::vector<std::string>& words,
                     const std::vector<std::pair<std::string, std::string>>& attrs, const std::string& doc,
                     bool hasDoc, Diagnostics& diags);

// Every format a pass stores (images, format_when=, an output's formats=) has a GLES form: ES
// stores it, the rule substitutes a format ES stores with as many channels of the same kind, or
// (an output's format only: the caller's choice) the rule refuses it.
void checkTargetRules(const Effect& e, Diagnostics& diags);

// The storage format `format` has on GLES; nullopt where the effect refuses it there (or, with no
// rule, where ES cannot store it).
std::optional<std::string> glesStorageFormat(const Effect& e, const std::string& format);

}  // namespace sao::codegen
