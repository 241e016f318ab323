#include "sao/inputs.h"

#include <algorithm>

namespace sao {
namespace {

const gen::ResourceInfo& info(gen::ResourceId input) { return gen::kResources[static_cast<std::size_t>(input)]; }

}  // namespace

bool isDepthInput(gen::ResourceId input) { return info(input).format == gen::Format::Depth; }

bool isRequiredInput(gen::ResourceId input) { return info(input).whenVariant < 0; }

bool mayBeMultisampled(gen::ResourceId input) {
  return std::any_of(gen::kVariants.begin(), gen::kVariants.end(), [&](const gen::VariantInfo& v) {
    return v.select == gen::VariantSelect::Multisampled && static_cast<gen::ResourceId>(v.selectIndex) == input;
  });
}

std::optional<gen::Format> formatOfGl(std::uint32_t glInternalFormat) {
  for (std::size_t f = 0; f < gen::kFormatInfo.size(); ++f)
    if (gen::kFormatInfo[f].colour && gen::kFormatInfo[f].glInternalFormat == glInternalFormat)
      return static_cast<gen::Format>(f);
  return std::nullopt;
}

std::optional<gen::Format> formatOfVk(std::uint32_t vkFormat) {
  for (std::size_t f = 0; f < gen::kFormatInfo.size(); ++f)
    if (gen::kFormatInfo[f].colour && gen::kFormatInfo[f].vkFormat == vkFormat) return static_cast<gen::Format>(f);
  return std::nullopt;
}

// The channels the effect reads from a colour input without formats=: the normals' follow their
// encoding (the camera's); any other input reads its format='s.
static std::uint32_t channelsRead(gen::ResourceId input, const Camera& camera) {
  return input == gen::ResourceId::normals ? normalsChannelsRead(camera.normalsEncoding)
                                           : gen::formatInfo(info(input).format).channels;
}

bool colourInputRefused(gen::ResourceId input, std::optional<gen::Format> format, std::uint32_t channels,
                        const Camera& camera) {
  const auto formats = info(input).formats;
  if (!formats.empty()) return !format || std::find(formats.begin(), formats.end(), *format) == formats.end();
  return channels == 0 || channels < channelsRead(input, camera);
}

Status checkColourInput(gen::ResourceId input, std::optional<gen::Format> format, std::uint32_t channels,
                        const Camera& camera, const std::string& image, const std::string& formatText,
                        std::string (*listName)(gen::Format), const char* noun) {
  const gen::ResourceInfo& r = info(input);
  if (!r.formats.empty()) {
    if (format && std::find(r.formats.begin(), r.formats.end(), *format) != r.formats.end()) return Status::success();
    std::string list;
    for (std::size_t i = 0; i < r.formats.size(); ++i)
      list += (i == 0 ? "" : i + 1 == r.formats.size() ? " or " : ", ") + listName(r.formats[i]);
    return Status::error(StatusCode::UnsupportedFormat,
                         image + " is " + formatText + "; " + std::string(r.name) + " must be " + list);
  }
  const std::uint32_t read = channelsRead(input, camera);
  if (channels == 0)
    return Status::error(StatusCode::UnsupportedFormat, image + " is " + formatText + "; the " + std::string(r.name) +
                                                            " input cannot be read from that format");
  if (channels >= read) return Status::success();
  if (input == gen::ResourceId::normals)
    return checkNormalsChannels(camera.normalsEncoding, channels, image + " is " + formatText, noun);
  return Status::error(StatusCode::UnsupportedFormat, image + " is " + formatText + " (" + std::to_string(channels) +
                                                          " channels); " + std::string(r.name) + " reads " +
                                                          std::to_string(read));
}

}  // namespace sao
