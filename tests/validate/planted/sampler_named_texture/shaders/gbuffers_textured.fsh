#version 330 compatibility
// The old atlas name hides texture() from GLSL 1.30 on.
uniform sampler2D texture;
in vec2 uv;
layout(location = 0) out vec4 outColor0;
void main() {
    outColor0 = texture(texture, uv);
}
