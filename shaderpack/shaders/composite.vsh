#version 330 compatibility
// Full-screen pass: one quad covering the screen. What depends on the uniforms alone is worked
// out here, once, rather than at every pixel.
#include "/lib/settings.glsl"
#include "/lib/common.glsl"
#include "/lib/waves.glsl"

uniform float frameTimeCounter;

out vec2 screenUv;
out vec2 ripple;

void main() {
    gl_Position = ftransform();
    screenUv = gl_MultiTexCoord0.xy;
    ripple = ripplePulse(frameTimeCounter);
}
