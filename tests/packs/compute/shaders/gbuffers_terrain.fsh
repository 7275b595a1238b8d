#version 120
// The terrain green, for the compute stages and composite to change.
void main() {
    gl_FragData[0] = vec4(0.0, 1.0, 0.0, 1.0);
}
