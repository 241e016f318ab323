// Depth and result images on disk: OpenEXR for depth (with the camera it was rendered with) and
// float intermediates, 8-bit PNG for the ambient-obscurance result.
//
// Row order, the same for every file written here: our images keep row 0 at the bottom (GL
// convention, see image.h), while EXR and PNG store their first scanline at the top of the screen.
// Writers therefore emit image row height-1 first and row 0 last, so a viewer shows the image the
// right way up, and readers undo it, so read(write(x)) == x. A foreign EXR is read the same way:
// its top scanline (lowest y of the data window) becomes row height-1. Camera::flipY is recorded
// but does not change the row order of the file.
//
// No exception escapes these functions: OpenEXR's exceptions (and any other) are caught and
// returned as a Status whose message names the path and the problem.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "sao/camera.h"
#include "sao/image.h"
#include "sao/status.h"

namespace sao {

// The value of the sao.version attribute this library writes and reads.
inline constexpr int kDepthExrVersion = 1;
// Most pixels an EXR reader accepts (8192 x 8192, or any shape of at most kMaxImageSide a side):
// 256 MiB a float channel.
inline constexpr std::uint64_t kMaxExrPixels = std::uint64_t(1) << 26;

// Writes a single-channel EXR (channel "Z", FLOAT, ZIP, data window (0,0)-(w-1,h-1)). D32F and
// LinearZ store the float bits exactly; D16 and D24 store the decoded normalised value
// decodeDepth(format, texel) as a float, which maps back to the same integer on reading.
//
// The camera and format are header attributes:
//   sao.version            int            1 (kDepthExrVersion)
//   sao.projection         m44d           x[i][j] = Camera::projection[i * 4 + j], i.e. x[c][r] is
//                                         element (row r, column c). That is the same transform in
//                                         Imath's row-vector convention (Imath's M44d is the
//                                         transpose of the column-vector GLM matrix).
//   sao.kind               string         "perspective" | "orthographic"
//   sao.clipDepth          string         "negativeOneToOne" | "zeroToOne"
//   sao.reversedZ          int            0 | 1
//   sao.infiniteFar        int            0 | 1
//   sao.flipY              int            0 | 1
//   sao.metersToViewUnits  double
//   sao.width              int            visible viewport, >= 0
//   sao.height             int
//   sao.guardBand          int
//   sao.depthFormat        string         "D16" | "D24" | "D32F" | "LinearZ"
// The depth extent must be (width + 2 guardBand) x (height + 2 guardBand). Errors: InvalidExtent
// for an empty image, InvalidInput for texels that do not match the extent or the format (D16/D24
// values above 2^n - 1), a non-finite camera or a camera whose size contradicts the extent,
// IoError when the file cannot be written.
Status writeDepthExr(const std::string& path, const DepthImage& depth, const Camera& camera);

// Reads a file written by writeDepthExr (hasCamera = true, depth and camera as written, texels
// bit-identical), or any flat EXR without a sao.version attribute whose depth channel is FLOAT or
// HALF (hasCamera = false, camera left untouched, depth read as D32F), as other tools write them:
//  - The depth channel, in any part of a multi-part file, is the one channel named "Z" or
//    "<layer>.Z" whose layer's last name is depth, any case ("depth.Z", Blender's
//    "ViewLayer.Depth.Z"; not "ViewLayer.Normal.Z"), or else the file's only channel. None or
//    several: IoError listing every part's channels.
//  - Any compression OpenEXR writes, DWAA and DWAB included. A lossy one (B44, B44A, DWAA, DWAB,
//    PXR24) leaves noise: hardware-depth texels at most kLossyDepthNoise outside [0, 1] are read
//    as 0 or 1 (counted in DepthFileInfo); farther ones stay and are refused downstream.
//  - The image is the display window. A data window inside it (a crop) is placed where it lies;
//    the texels around it hold no surface (EXR: nothing outside the data window), so they are
//    sky: the clear value of the file's camera (0 reversed-Z, else 1; LinearZ +0), or
//    DepthReadOptions::skyWithoutCamera. At most kMaxExrPixels, and at most kMaxCropFillPixels
//    more than the data window (a small file cannot make a large image). A data window that
//    reaches outside the display window is refused naming both, unless it has the display
//    window's size (an offset origin: read as the image, as before).
// A file with sao.version must carry every attribute above with the right type; sao.projection
// may also be m44f (what OpenImageIO and Python write).
// Errors: IoError for missing files, directories and other non-regular files (FIFOs, devices),
// files that are not EXR, truncated or corrupt files, wrong channel counts, missing or mistyped
// attributes, non-finite camera values, an extent that contradicts width/height/guardBand, data
// windows larger than kMaxImageSide a side or kMaxExrPixels in all, headers that declare more
// chunks than the file can hold; UnsupportedFormat
// for an unknown sao.version, format, kind or clipDepth string, subsampled channels and UINT
// channels. On error `depth`, `camera` and `hasCamera` are left unchanged.
// Reading never allocates by what a header declares before the file is known to hold that much:
// headers are parsed by OpenEXR's core library within a fixed memory budget, and the image grows
// as its chunks decode.
Status readDepthExr(const std::string& path, DepthImage& depth, Camera& camera, bool& hasCamera);

// How far outside [0, 1] a hardware-depth texel of a lossily compressed file may lie and still be
// read as 0 or 1: four binary16 steps just below 1 (2^-9). B44 on a HALF sky of 0 gives -6e-6.
inline constexpr float kLossyDepthNoise = 1.0f / 512.0f;
// Most texels of the display window a crop may leave to be filled (32 MiB of D32F).
inline constexpr std::uint64_t kMaxCropFillPixels = std::uint64_t(1) << 23;

struct DepthReadOptions {
  // The texel value around a cropped data window of a file without a camera: its sky (1 for
  // standard depth, 0 for reversed-Z, +inf for distances). Ignored for files with a camera.
  float skyWithoutCamera = 1.0f;
};

// What readDepthExr learnt of the file besides the depth and the camera, for messages.
struct DepthFileInfo {
  bool hasCamera = false;
  std::uint32_t part = 0, parts = 1;  // the part read, of how many
  std::string channel;                // the depth channel's name
  bool storedAsHalf = false;          // binary16 in the file: about 3 significant digits
  std::string compression;            // "ZIP", "B44", "DWAA", ...
  bool lossy = false;                 // B44, B44A, DWAA, DWAB or PXR24
  std::uint64_t lossyNoiseTexels = 0; // texels moved into [0, 1] (see kLossyDepthNoise)
  float lossyNoiseWorst = 0;          // the farthest of them, as stored (e.g. -6e-6)
  std::uint64_t cropFillTexels = 0;   // texels outside the data window, filled with sky
  std::vector<std::string> saoAttributes;  // camera attributes (sao.kind, ...) of a file without sao.version
};

// readDepthExr with what it learnt of the file and the sky around a crop (see above). The
// overload above is this one with default options.
Status readDepthExr(const std::string& path, DepthImage& depth, Camera& camera, DepthFileInfo& info,
                    const DepthReadOptions& options = {});

// Writes one channel of `ao` as an 8-bit grey PNG, value round(clamp(v, 0, 1) * 255), image row
// height-1 first (the top of the screen, see above): the first PNG pixel is ao.at(0, height-1).
// A NaN is never written: InvalidInput naming the first NaN pixel (row 0 first, then x). +-inf
// clamp to 255 / 0. Errors: InvalidExtent for an empty image, InvalidInput for a channel out of
// range or data that does not match the extent, IoError when the file cannot be written.
Status writeAoPng(const std::string& path, const FloatImage& ao, std::uint32_t channel = 0);

// Dumps a float image (intermediates) as an EXR with one FLOAT channel per image channel, named by
// channelNames (one per channel, non-empty, distinct), same row order as the depth EXR. EXR sorts
// channels by name, so the order is also kept in a stringvector attribute sao.channels.
Status writeFloatExr(const std::string& path, const FloatImage& image, const std::vector<std::string>& channelNames);

// Reads any flat EXR with FLOAT or HALF channels as a FloatImage: channel order from sao.channels
// when it names exactly the file's channels, otherwise the file's (alphabetical) order.
// readFloatExr(writeFloatExr(x)) gives back x and its names bit for bit. Errors as readDepthExr.
Status readFloatExr(const std::string& path, FloatImage& image, std::vector<std::string>& channelNames);

}  // namespace sao
