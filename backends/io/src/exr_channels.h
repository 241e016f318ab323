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

// Whether a channel name names depth: "Z", or "<layer>.Z" whose layer's last name is "depth" in
// any case ("depth.Z", Blender's "ViewLayer.Depth.Z"; not "ViewLayer.Normal.Z", "Vector.Z").
bool isDepthChannelName(const std::string& name);

// The depth channel of a file (sao/io.h): the one depth-named channel among every part's, or the
// file's only channel. IoError listing every part's channels when there is none or several.
struct DepthChannel {
  int part = 0;
  std::string name;
};
Status findDepthChannel(const std::string& path, const std::vector<exr::PartInfo>& parts, DepthChannel& out);

}  // namespace sao::io::detail
