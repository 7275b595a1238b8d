#version 330 compatibility
// Packs a material id and a flag into an unsigned integer buffer (R32UI, stored as RGBA32UI):
// the scene's red byte, a bit for bright pixels and a marker that shows the bits arrive whole.
/*
const int colortex1Format = R32UI;
*/
uniform sampler2D colortex0;
in vec2 uv;
/* RENDERTARGETS: 1 */
layout(location = 0) out uint bits;
void main() {
    vec3 scene = texture(colortex0, uv).rgb;
    uint red = uint(scene.r * 255.0 + 0.5);
    uint bright = scene.g > 0.5 ? 1u : 0u;
    bits = red | (bright << 8u) | (0xABCDu << 16u);
}
