#version 330 compatibility
in vec2 uv;
layout(location = 1) out vec4 extra;
void main() {
    gl_FragData[0] = vec4(uv, 0.0, 1.0);
    extra = vec4(1.0);
}
