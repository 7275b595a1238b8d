#version 120
void main() {
/* DRAWBUFFERS:0 */
    gl_FragData[0] = vec4(0.25, 0.5, 0.75, 1.0);
}
