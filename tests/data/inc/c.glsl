#ifndef C_GLSL
#define C_GLSL
const float C = 3.0;
#endif
