// Includes cycle_b, which includes this file again.
#include "cycle_b.glsl"
