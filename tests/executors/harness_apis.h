// What each API's half of the harness gives harness.cpp (not for the tests themselves).
#pragma once
#include <memory>
#include <vector>

#include "harness.h"

namespace sao::exectest {

std::unique_ptr<Executor> makeGlExecutor();
void glMessagesBefore();  // context current, pending debug messages cleared
void glMessagesAfter();   // every GL debug error since fails the test

std::unique_ptr<Executor> makeVkExecutor();
void vkMessagesBefore();
void vkMessagesAfter();

// The engine-side example on the Vulkan context (its messages are the context's: vkMessages*).
std::unique_ptr<Executor> makeEngineExecutor();

// sao::gles on its own headless ES 3.1 context (not the GL executor's).
std::unique_ptr<Executor> makeGlesExecutor();
void glesMessagesBefore();  // the ES context current, pending debug messages cleared
void glesMessagesAfter();   // every ES debug error since fails the test

// The library's APIs built into the harness (GL, Vulkan); apis() adds the engine and GLES per program.
std::vector<Api> libraryApis();

}  // namespace sao::exectest

namespace sao::exectest {

// `image` with `channels` channels: the first ones kept, missing ones 0 (normals' .xy for an RG
// texture, motion's .xy padded for an RGBA one).
FloatImage withChannels(const FloatImage& image, std::uint32_t channels);
std::uint32_t channelsOf(Texels texels);
std::uint32_t channelsOf(gen::Format format);  // the generated format table's
// Refuses a stereo frame (Frame::depthLayers) beyond what the halves upload as arrays.
Status checkLayers(const Frame& frame);
// The depth a run reads: Frame::depth, or the layer's.
inline const DepthImage& runDepth(const Frame& f) { return f.depthLayers.empty() ? *f.depth : *f.depthLayers.at(f.layer); }

}  // namespace sao::exectest
