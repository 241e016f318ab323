// Turns the loaded source into the Effect model, checking every declaration.
#pragma once
#include "diagnostics.h"
#include "effect_model.h"
#include "source_loader.h"

namespace sao::codegen {

Effect parseEffect(const LoadedSource& source, Diagnostics& diags);

}  // namespace sao::codegen
