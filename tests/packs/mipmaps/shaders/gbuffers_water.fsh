#version 120
// No DRAWBUFFERS: OptiFine draws output 0 into colortex0, Iris too.
void main() {
    gl_FragData[0] = vec4(0.2, 0.4, 0.8, 0.5);
}
