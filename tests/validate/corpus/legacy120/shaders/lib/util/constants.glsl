#ifndef CONSTANTS_GLSL
#define CONSTANTS_GLSL
const float PI = 3.14159265;
#define TAU (2.0 * PI)
#endif
