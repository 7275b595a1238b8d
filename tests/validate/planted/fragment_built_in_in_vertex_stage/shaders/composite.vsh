#version 330 compatibility
// A helper shared with fragment stages, kept out of them by a switch a player can turn off:
// off, the vertex stage holds a function that reads gl_FragCoord, which it does not have.
uniform float viewWidth;
out vec2 uv;
bool insideViewport() {
    return all(lessThan(gl_FragCoord.xy, vec2(viewWidth)));
}
void main() {
    gl_Position = ftransform();
    uv = gl_MultiTexCoord0.xy;
}
