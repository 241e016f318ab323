// A library file with a GLSL syntax error on line 3.
float ok_fn(float x) { return x; }
float broken_fn(float x) { return x +* 2.0; }
