// tinygltf's implementation, with the settings of tinygltf.h.
#define TINYGLTF_IMPLEMENTATION
#include "tinygltf.h"
