#version 400 compatibility
// Gathers from colortex0 (red, green, and an offset one of blue), a quarter texel off the
// texel's centre so that which texels they take does not hang on the last bit of the
// coordinate. The render path lowers them to texel fetches; Mesa gathers in hardware.
uniform sampler2D colortex0;
uniform float viewWidth;
uniform float viewHeight;
in vec2 texcoord;
/* RENDERTARGETS: 0 */
layout(location = 0) out vec4 color;
void main() {
    vec2 p = texcoord + 0.25 / vec2(viewWidth, viewHeight);
    vec4 red = textureGather(colortex0, p);
    vec4 green = textureGather(colortex0, p, 1);
    vec4 blue = textureGatherOffset(colortex0, p, ivec2(-3, 2), 2);
    color = vec4(dot(red, vec4(0.4, 0.3, 0.2, 0.1)), dot(green, vec4(0.1, 0.2, 0.3, 0.4)), dot(blue, vec4(0.25)), 1.0);
}
