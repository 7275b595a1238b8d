#version 330 compatibility
// As seilotte/lumina aligns its shadow map: a mat2 built from one vec4 uniform, which
// GLSL fills column by column from the vector's components.
uniform vec4 entityColor;
void main() {
    gl_Position = ftransform();
    gl_Position.xy = mat2(entityColor) * gl_Position.xy;
}
