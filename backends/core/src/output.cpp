#include "sao/output.h"

#include <algorithm>

namespace sao {

std::span<const gen::Format> outputFormats() {
  const auto& ao = gen::kResources[static_cast<std::size_t>(gen::ResourceId::ao)];
  return ao.formats;
}

bool isOutputFormat(gen::Format format) {
  const auto list = outputFormats();
  return std::find(list.begin(), list.end(), format) != list.end();
}

std::uint32_t channelCount(gen::Format format) { return gen::formatInfo(format).channels; }

const char* formatName(gen::Format format) { return gen::formatInfo(format).name.data(); }  // a literal

Status checkOutputChannels(gen::Format format, std::uint32_t mask, const char* who) {
  if (mask == kAllChannels) return Status::success();
  const std::uint32_t has = (1u << channelCount(format)) - 1u;
  if (mask != 0 && (mask & ~has) == 0) return Status::success();
  return Status::error(StatusCode::InvalidInput,
                       std::string(who) + ": the output channel mask " + std::to_string(mask) + " does not fit a " +
                           formatName(format) + " output: give kAllChannels (15) or a non-empty set of its channels (" +
                           (channelCount(format) == 1 ? "R = 1" : "R = 1, G = 2, B = 4, A = 8") + ")");
}

std::int32_t outputMaskParam(std::uint32_t mask) { return static_cast<std::int32_t>(mask & kAllChannels); }

bool keepsChannels(gen::Format format, std::uint32_t mask, OutputBlend blend) {
  const std::uint32_t has = (1u << channelCount(format)) - 1u;
  return blend == OutputBlend::Multiply || (has & ~mask) != 0;
}

const char* toString(OutputBlend blend) {
  switch (blend) {
    case OutputBlend::Replace: return "replace";
    case OutputBlend::Multiply: return "multiply";
  }
  return "?";
}

Status checkOutputBlend(OutputBlend blend, bool userOutput, const char* who) {
  if (blend != OutputBlend::Replace && blend != OutputBlend::Multiply)
    return Status::error(StatusCode::InvalidInput, std::string(who) + ": unknown output blend " +
                                                       std::to_string(int(blend)) + " (replace 0, multiply 1)");
  if (blend == OutputBlend::Multiply && !userOutput)
    return Status::error(StatusCode::InvalidInput,
                         std::string(who) + ": output blend multiply needs your own output (it multiplies A into "
                                            "its texels); an effect-owned output holds nothing to multiply");
  return Status::success();
}

std::string outputFormatList() {
  std::string s;
  for (gen::Format f : outputFormats()) s += (s.empty() ? "" : ", ") + std::string(formatName(f));
  return s;
}

}  // namespace sao
