#version 330 compatibility
out Varyings {
    flat int material;
    vec2 uv;
} vs;
void main() {
    gl_Position = ftransform();
    vs.material = int(gl_MultiTexCoord1.x);
    vs.uv = gl_MultiTexCoord0.xy;
}
