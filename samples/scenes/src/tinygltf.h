// Private to sao_scenes: <tiny_gltf.h> (Debian's libtinygltf-dev, 2.7.0) with the same settings in
// every file that includes it. Only geometry is read: no image decoding or writing (no stb_image),
// no external image files; tinygltf_impl.cpp compiles its implementation into sao_scenes, so that
// these settings hold and the fuzz build instruments it (Debian's libtinygltf.so is not linked).
#pragma once
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
