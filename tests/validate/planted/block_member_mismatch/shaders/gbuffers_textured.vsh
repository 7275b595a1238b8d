#version 330 compatibility
out Surface {
    vec2 uv;
    vec4 tint;
} vs;
void main() {
    gl_Position = ftransform();
    vs.uv = gl_MultiTexCoord0.xy;
    vs.tint = gl_Color;
}
