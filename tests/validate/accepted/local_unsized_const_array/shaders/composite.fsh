#version 330 compatibility
uniform sampler2D colortex0;
in vec2 uv;
layout(location = 0) out vec4 outColor0;
void main() {
    // Unsized, sized by its initializer (GLSL 1.20 §4.1.9); naga needs the size written.
    const vec2 offsets[] = vec2[4](vec2(1.0, 0.0), vec2(-1.0, 0.0), vec2(0.0, 1.0), vec2(0.0, -1.0));
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 4; i++) {
        sum += texture(colortex0, uv + offsets[i] * 0.001);
    }
    outColor0 = sum * 0.25;
}
