#define VERTEX_STAGE
#include "/lib/version.glsl"
// As seilotte/lumina starts every program: a `#define` before the include that holds
// `#version`, which Iris hoists and OptiFine hands to the driver as written.
out vec2 uv;
void main() {
    gl_Position = ftransform();
    uv = gl_MultiTexCoord0.xy;
}
