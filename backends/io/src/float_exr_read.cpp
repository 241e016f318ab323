// readFloatExr: any flat EXR of FLOAT or HALF channels as a FloatImage. See sao/io.h.
#include <algorithm>
#include <string>
#include <vector>

#include "exr_channels.h"
#include "exr_reader.h"
#include "io_checks.h"
#include "sao/io.h"

namespace sao {
namespace {

using namespace io::detail;

Status readFloatImpl(const std::string& path, FloatImage& image, std::vector<std::string>& channelNames) {
  exr::Input in;
  if (Status s = in.open(path); !s) return s;
  std::vector<std::string> names;
  for (const exr::ChannelInfo& c : in.channels()) {
    if (Status s = checkChannel(path, c); !s) return s;
    names.push_back(c.name);
  }
  if (names.empty()) return fail(StatusCode::IoError, path, "has no channels");
  std::vector<std::string> order;
  bool found = false;
  // An order of another type, or one that does not name exactly the file's channels, is ignored.
  if (in.stringVectorAttribute("sao.channels", found, order) && found) {
    std::vector<std::string> sortedOrder = order, sortedNames = names;
    std::sort(sortedOrder.begin(), sortedOrder.end());
    std::sort(sortedNames.begin(), sortedNames.end());
    if (sortedOrder == sortedNames) names = order;
  }

  FloatImage out;
  out.extent = in.extent();
  out.channels = std::uint32_t(names.size());
  if (Status s = in.readChannels(names, out.data); !s) return s;
  image = std::move(out);
  channelNames = std::move(names);
  return Status::success();
}

}  // namespace

Status readFloatExr(const std::string& path, FloatImage& image, std::vector<std::string>& channelNames) {
  return guarded(path, "read the EXR", [&] { return readFloatImpl(path, image, channelNames); });
}

}  // namespace sao
