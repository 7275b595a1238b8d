#version 330 compatibility
// The integer member lacks `flat` here (GLSL 1.30 4.3.4).
in Varyings {
    int material;
    vec2 uv;
} fs;
layout(location = 0) out vec4 outColor0;
void main() {
    outColor0 = vec4(fs.uv, float(fs.material), 1.0);
}
