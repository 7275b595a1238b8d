#version 330 compatibility
flat out mat2x3 lightColor;
void main() {
    gl_Position = ftransform();
    lightColor = mat2x3(vec3(1.0), vec3(0.5));
}
