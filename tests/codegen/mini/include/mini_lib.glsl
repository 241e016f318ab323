// Shared library code of the mini effect.
float mini_twice(float x) { return 2.0 * x; }
