#version 330 compatibility
// Two output blocks beside a plain varying.
out vec2 uv;
out Material {
    flat int kind;
    vec3 normal;
} material;
out Lighting {
    vec2 lm;
};
void main() {
    gl_Position = ftransform();
    uv = gl_MultiTexCoord0.xy;
    material.kind = int(gl_MultiTexCoord1.x);
    material.normal = gl_NormalMatrix * gl_Normal;
    lm = gl_MultiTexCoord1.xy / 240.0;
}
