// Closes the cycle.
#include "cycle_a.glsl"
