uniform sampler2D colortex0;

#include "tonemap.glsl"
vec3 post(vec2 uv) { return texture2D(colortex0, uv).rgb; }
