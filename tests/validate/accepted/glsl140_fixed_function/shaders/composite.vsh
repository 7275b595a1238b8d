#version 140
// GLSL 1.40 has no profiles: a compatibility context (ARB_compatibility) keeps the fixed-function
// built-ins, and Mesa compiles them.
out vec2 texcoord;
void main() {
    gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;
    texcoord = gl_MultiTexCoord0.xy;
}
