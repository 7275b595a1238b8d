#version 120
// As magwer/Roselle-Shader's Nether composite: the vertex stage writes two components of a
// vec3 varying, and the fragment stage reads the third too, which Mesa's linker refuses.
varying vec3 texcoord;
void main() {
    gl_Position = ftransform();
    texcoord.st = gl_MultiTexCoord0.st;
}
