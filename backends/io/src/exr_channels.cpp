// Channel checks of the EXR readers; see exr_channels.h.
#include "exr_channels.h"

#include <cctype>

#include "io_checks.h"

namespace sao::io::detail {

Status checkChannel(const std::string& path, const exr::ChannelInfo& c) {
  if (c.pixelType != EXR_PIXEL_FLOAT && c.pixelType != EXR_PIXEL_HALF)
    return fail(StatusCode::UnsupportedFormat, path,
                "channel \"" + c.name + "\" is " + (c.pixelType == EXR_PIXEL_UINT ? "UINT" : "of an unknown pixel type") +
                    "; only FLOAT and HALF channels are read");
  if (c.xSampling != 1 || c.ySampling != 1)
    return fail(StatusCode::UnsupportedFormat, path, "channel \"" + c.name + "\" is subsampled; only full-resolution channels are read");
  return Status::success();
}

std::string channelList(const std::vector<exr::ChannelInfo>& channels) {
  std::string s;
  for (const exr::ChannelInfo& c : channels) s += std::string(s.empty() ? "" : ", ") + c.name;
  return s.empty() ? "none" : s;
}

bool isDepthChannelName(const std::string& name) {
  if (name == "Z") return true;
  if (name.size() < 2 || name.compare(name.size() - 2, 2, ".Z") != 0) return false;
  const std::string layer = name.substr(0, name.size() - 2);
  const std::size_t dot = layer.rfind('.');
  std::string last = dot == std::string::npos ? layer : layer.substr(dot + 1);
  for (char& c : last) c = char(std::tolower(static_cast<unsigned char>(c)));
  return last == "depth";
}

Status findDepthChannel(const std::string& path, const std::vector<exr::PartInfo>& parts, DepthChannel& out) {
  std::vector<DepthChannel> candidates;
  std::size_t total = 0;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    total += parts[p].channels.size();
    for (const exr::ChannelInfo& c : parts[p].channels)
      if (isDepthChannelName(c.name)) candidates.push_back({int(p), c.name});
  }
  if (candidates.size() == 1) {
    out = candidates[0];
    return Status::success();
  }
  if (candidates.empty() && total == 1) {
    for (std::size_t p = 0; p < parts.size(); ++p)
      if (!parts[p].channels.empty()) out = {int(p), parts[p].channels[0].name};
    return Status::success();
  }
  const std::string rule = "a depth file needs exactly one channel named Z or <layer>.Z with a layer named depth "
                           "(depth.Z, ViewLayer.Depth.Z), or exactly one channel";
  if (parts.size() == 1)
    return fail(StatusCode::IoError, path,
                "has " + std::to_string(total) + " channels (" + channelList(parts[0].channels) + ") and " +
                    (candidates.empty() ? "none is a depth channel; " : "several are depth channels; ") + rule);
  std::string list;
  for (std::size_t p = 0; p < parts.size(); ++p)
    list += (p ? "; part " : "part ") + std::to_string(p) + (parts[p].name.empty() ? "" : " \"" + parts[p].name + "\"") +
            ": " + channelList(parts[p].channels);
  return fail(StatusCode::IoError, path,
              "has " + std::to_string(parts.size()) + " parts and " +
                  (candidates.empty() ? "no depth channel" : std::to_string(candidates.size()) + " depth channels") +
                  " (" + list + "); " + rule);
}

}  // namespace sao::io::detail
