// Channel checks of the EXR readers; see exr_channels.h.
#include "exr_channels.h"

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

}  // namespace sao::io::detail
