#include "b.glsl"
