// Which channels the EXR readers accept: FLOAT or HALF at full resolution.
#pragma once
#include <string>
#include <vector>

#include "exr_reader.h"
#include "sao/status.h"

namespace sao::io::detail {

// UnsupportedFormat naming the channel for a UINT or unknown pixel type and for a subsampled one.
Status checkChannel(const std::string& path, const exr::ChannelInfo& c);

// "B, G, R" (or "none"), for messages about the file's channels.
std::string channelList(const std::vector<exr::ChannelInfo>& channels);

}  // namespace sao::io::detail
