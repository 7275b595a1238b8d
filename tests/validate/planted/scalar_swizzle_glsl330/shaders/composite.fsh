#version 330 compatibility
// A swizzle of a scalar needs GLSL 4.20.
uniform sampler2D colortex0;
in vec2 uv;
layout(location = 0) out vec4 outColor0;
float luma(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }
void main() {
    vec3 c = texture(colortex0, uv).rgb;
    outColor0 = vec4(luma(c).rrr, 1.0);
}
