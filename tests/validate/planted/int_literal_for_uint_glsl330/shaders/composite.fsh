#version 330 compatibility
in vec2 uv;
out vec4 colour;
void main() {
    uint n = 3;
    colour = vec4(float(n) * uv.x);
}
