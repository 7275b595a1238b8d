#version 420 compatibility
// GLSL 4.20 swizzles scalars: of a call, a variable, a parenthesised sum, an integer.
uniform sampler2D colortex0;
in vec2 uv;
layout(location = 0) out vec4 outColor0;
float luma(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }
int level(float x) { return int(x * 4.0); }
void main() {
    vec3 c = texture(colortex0, uv).rgb;
    float l = luma(c).r;
    vec3 grey = luma(c).rrr;
    vec2 pair = (l + uv.x).xx;
    ivec2 steps = level(l).ss;
    outColor0 = vec4(grey * l.x + vec3(pair, 0.0), float(steps.y));
}
