// No #version: GLSL 1.10, which converts nothing implicitly. Drivers other than NVIDIA refuse
// `18. + 258 * 2`; found in a released pack's viewport scale.
uniform vec2 texelSize;
varying vec2 uv;
void main() {
    vec2 scale = vec2(18. + 258 * 2, 258.) * texelSize;
    gl_Position = vec4(gl_Vertex.xy * scale, 0.0, 1.0);
    uv = gl_MultiTexCoord0.xy;
}
