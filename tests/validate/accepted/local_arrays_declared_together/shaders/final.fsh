#version 330 compatibility
// As yanis-dubois/BloomingLightShader gathers its frustum planes: two local arrays in one
// declaration, each filled through an `out` array parameter.
in vec2 uv;
void planes(out vec3 normals[6], out vec3 points[6]) {
    for (int i = 0; i < 6; i++) {
        normals[i] = vec3(i);
        points[i] = vec3(uv, i);
    }
}
void main() {
    vec3 normals[6], points[6];
    planes(normals, points);
    gl_FragColor = vec4(normals[2] + points[3], 1.0);
}
