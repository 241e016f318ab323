#include "help.h"

#include <algorithm>
#include <sstream>
#include <string_view>

#include "sao/io.h"
#include "sao/settings.h"

namespace sao::render {
namespace {

std::string number(double v) {
  std::ostringstream s;
  s.precision(9);  // as the range errors print them: 0.1, not 0.10000000000000001
  s << v;
  return s.str();
}

// `text` wrapped at `width` columns, every line indented by `indent` spaces.
std::string wrapped(std::string_view text, std::size_t indent, std::size_t width) {
  std::string out, line;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view word = text.substr(start, end - start);
    if (!line.empty() && indent + line.size() + 1 + word.size() > width) {
      out += std::string(indent, ' ') + line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + std::string(word);
    start = end + 1;
  }
  if (!line.empty()) out += std::string(indent, ' ') + line + "\n";
  return out;
}

}  // namespace

std::string settingsHelp() {
  std::ostringstream s;
  s << "\nSettings (--set NAME=VALUE; range, unit and default from the effect's metadata):\n";
  for (const auto& info : gen::kSettings) {
    std::string range;
    switch (info.type) {
      case gen::SettingType::Bool: range = "0 | 1"; break;
      case gen::SettingType::Int:
        range = "whole number in [" + number(info.minValue) + ", " + number(info.maxValue) + "]";
        if (!info.allowedValues.empty()) {  // values=[...]: those alone
          range = "one of";
          for (std::size_t i = 0; i < info.allowedValues.size(); ++i)
            range += std::string(i ? " |" : "") + " " + number(info.allowedValues[i]);
        }
        break;
      case gen::SettingType::Float: range = "[" + number(info.minValue) + ", " + number(info.maxValue) + "]"; break;
    }
    std::string name(info.name);
    name.resize(std::max<std::size_t>(name.size(), 20), ' ');
    s << "  " << name << "  " << range << ", " << (info.unit.empty() ? std::string("unitless") : std::string(info.unit))
      << ", default " << number(info.defaultValue) << "\n"
      << wrapped(info.doc, 24, 100);
    // The effect's inert rules: the setting has no effect then, and --set refuses it.
    for (const auto& rule : gen::kInertRules)
      if (gen::kSettings[static_cast<std::size_t>(rule.setting)].name == info.name)
        s << wrapped("No effect while " + std::string(rule.whenText) + " (" + std::string(rule.reason) +
                         "): --set refuses it then.",
                     24, 100);
  }
  return s.str();
}

std::string depthExrHelp() {
  std::ostringstream s;
  s << "\nDepth EXR files (--depth reads them, --save-depth writes them): one FLOAT channel \"Z\" of\n"
       "hardware depth (D16/D24 as the normalised value, D32F as is, LinearZ as camera-space z). The\n"
       "camera travels in header attributes (sao/io.h):\n"
       "  sao.version int (" << kDepthExrVersion << ")   sao.projection m44d (x[c][r] = the matrix's row r, column c)\n"
       "  sao.kind \"perspective\"|\"orthographic\"   sao.clipDepth \"negativeOneToOne\"|\"zeroToOne\"\n"
       "  sao.reversedZ, sao.infiniteFar, sao.flipY int 0|1   sao.metersToViewUnits double\n"
       "  sao.width, sao.height, sao.guardBand int (the depth is (width+2*guardBand) x (height+2*guardBand))\n"
       "  sao.depthFormat \"D16\"|\"D24\"|\"D32F\"|\"LinearZ\"\n"
       "A file without sao.version is read as D32F hardware depth (channel \"Z\", else its only\n"
       "channel) and needs the camera as options: --fovy, --near, --far, --clip, --reversed-z, --guard;\n"
       "with --depth-distances it holds distances along the view axis (a Blender Z pass) instead.\n"
       "Files of other tools: any compression (DWAA/DWAB too; lossy noise just outside [0, 1] is read as\n"
       "0 or 1, with a warning); the depth channel in any part: \"Z\", or \"<layer>.Z\" whose layer is\n"
       "named depth (Blender's ViewLayer.Depth.Z, depth.Z); sao.projection as m44f too. The image is the\n"
       "display window: a data window cropped inside it is placed there with sky around it.\n"
       "Not detectable, so the AO is wrong without a word: NDC z (GL's [-1, 1]) stored instead of window\n"
       "depth (most of it lies in [0, 1]); a guard band the file was rendered with but that --guard (or\n"
       "sao.guardBand) does not declare (the field of view is then wrong). Binary16 (HALF) standard depth\n"
       "is warned about with the depth step it leaves against the radius.\n";
  return s.str();
}

std::string depthConventionHelp() {
  return "\nDepth values that do not fit the conventions they are read with are warned about (exit 0;\n"
         "the units/radius warnings are left out then: a wrong convention explains their figures):\n"
         "no geometry at all (every texel sky: the clear value, e.g. a near plane beyond the scene;\n"
         "LinearZ holding positive distances: --depth-distances); reversed-Z depth read without\n"
         "--reversed-z, or standard depth read with it (perspective: most geometry within twice the near\n"
         "distance, where only the wrong reading puts it; a sky of the other convention's clear value);\n"
         "linear depth normalised to [0, 1] read as window depth (on flat surfaces 1/d, not d, changes\n"
         "evenly across the image). Not detectable: the Z convention of orthographic depth without sky\n"
         "(it is affine in the distance either way), linear [0, 1] depth with --ortho (that is\n"
         "orthographic window depth for some near and far), and perspective depth read with the wrong Z\n"
         "convention whose geometry lies mostly within twice the near distance.\n";
}

}  // namespace sao::render
