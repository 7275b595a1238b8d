#version 330 compatibility
// No vertex output block is named `Light`.
uniform sampler2D colortex0;
in vec2 uv;
in Light {
    vec3 color;
} light;
layout(location = 0) out vec4 outColor0;
void main() {
    outColor0 = texture(colortex0, uv) * vec4(light.color, 1.0);
}
