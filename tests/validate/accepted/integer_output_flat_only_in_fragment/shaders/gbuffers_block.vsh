#version 450 compatibility
// The vertex side leaves the integer output unqualified: from GLSL 1.50 on only the
// fragment input must be flat, and drivers take the fragment side's qualifier.
uniform int blockEntityId;
out int entityMark;
void main() {
    entityMark = blockEntityId;
    gl_Position = ftransform();
}
