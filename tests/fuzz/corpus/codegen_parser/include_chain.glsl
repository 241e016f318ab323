#pragma sao effect inc version=3
#include "include/sao_depth.glsl"
#include "inc/broken.glsl"
#include   "include/mini_lib.glsl"   // trailing comment
#include <angle.glsl>
#pragma sao setting bool on default=false "doc"
