#version 330 compatibility
// `x` is a uint parameter in one function and an int loop counter in main: the literal is
// compared with the int.
uniform sampler2D colortex0;
in vec2 texcoord;
uint halve(uint x) {
    return x >> 1u;
}
/* RENDERTARGETS: 0 */
layout(location = 0) out vec4 colour;
void main() {
    vec3 sum = vec3(0.0);
    for (int x = -2; x <= 2; x += 1) {
        sum += texture(colortex0, texcoord + vec2(float(x) * 0.001, 0.0)).rgb;
    }
    colour = vec4(sum / float(halve(10u)), 1.0);
}
