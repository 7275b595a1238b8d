#version 120
// Red on a face's front, blue on its back. The game culls back faces, so every face on screen
// is a front face: the terrain is red.
void main() {
    gl_FragData[0] = gl_FrontFacing ? vec4(1.0, 0.0, 0.0, 1.0) : vec4(0.0, 0.0, 1.0, 1.0);
}
