// sao-render's --depth file beyond reading it: what the reader's DepthFileInfo means for the user
// (notes on stderr and in the summary), --depth-distances, and the precision binary16 leaves.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "sao/camera.h"
#include "sao/image.h"
#include "sao/io.h"
#include "sao/status.h"

namespace sao::render {

// What the reader did to the file's values, one line each: lossy-compression noise read as 0 or 1,
// a cropped data window filled with sky. Empty for a plain file.
std::vector<std::string> depthFileNotes(const std::string& path, const DepthFileInfo& info);

// --depth-distances: the file holds positive distances along the view axis (a Blender Z pass, in
// the file's units), read as D32F. Turns them into LinearZ (z = -distance); sky, i.e. a distance
// at or above `far`, not finite, or 0, becomes +0 (LinearZ's sky). InvalidInput for a negative
// distance (camera-space z is negative in front: that is LinearZ, not distances).
Status distancesToLinearZ(DepthImage& depth, double far);

// When the file stored the depth as binary16: the distance between the depth of the median surface
// texel and that of the next binary16 value, in metres. Standard depth (1 at the far plane) keeps
// about 11 bits near 1 and so loses metres at a few metres' distance: a warning naming the step
// against the radius when it exceeds kHalfDepthStepOfRadius of it; nullopt otherwise (or with no
// surface texel).
inline constexpr double kHalfDepthStepOfRadius = 0.02;
std::optional<std::string> halfPrecisionWarning(const std::string& path, const DepthImage& depth, const Camera& camera,
                                                double radiusMeters);

}  // namespace sao::render
