#version 130
out vec2 uv;
flat out int id;
void main() {
 gl_Position = ftransform();
 uv = gl_MultiTexCoord0.xy; id = 1;
}
