#version 120
// The shadow pass: every caster writes one colour into shadowcolor0.
void main() {
    gl_Position = ftransform();
}
