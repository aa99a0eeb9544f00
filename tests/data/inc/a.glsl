#ifndef A_GLSL
#define A_GLSL
#include "sub/b.glsl"
float a() { return b(); }
#endif
