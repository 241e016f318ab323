// sao-bench --sections traffic: the memory-traffic model (traffic_model.h) over the radius sweep
// and the resolution table, for SAO, SAO without the hierarchy and the AlchemyAO-style baseline,
// on a paper-like GTX 680 (and the same with a 48 KB L1) and on this CPU. Writes traffic.csv and
// prints a summary.
#pragma once
#include <functional>
#include <string>

#include "sao/camera.h"
#include "sao/image.h"
#include "sao/status.h"

namespace sao::bench {

struct TrafficInput {
  const DepthImage* depth = nullptr;
  Camera camera;
};

// sceneAt(extent): the main scene's depth and camera at that size (sao-bench's prepared scene).
Status trafficSection(const std::string& outDir, const std::string& sceneName, bool quick,
                      const std::function<TrafficInput(Extent)>& sceneAt);

}  // namespace sao::bench
