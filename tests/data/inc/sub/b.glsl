#ifndef B_GLSL
#define B_GLSL
#include "../c.glsl"
float b() { return 2.0; }
#endif
