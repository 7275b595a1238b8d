#version 120
// `N` in OptiFine's list: output 0 is drawn into no buffer, output 1 into colortex0, so the
// terrain is green, never red.
void main() {
    /* DRAWBUFFERS:N0 */
    gl_FragData[0] = vec4(1.0, 0.0, 0.0, 1.0);
    gl_FragData[1] = vec4(0.0, 1.0, 0.0, 1.0);
}
