#version 430 compatibility
uniform sampler2D colortex0;
in Transforms {
    vec2 uv;
    mat4 modelView;
    mat3 basis;
} fs_in;
void main() {
    vec3 lit = mat3(fs_in.modelView) * fs_in.basis[2];
    gl_FragData[0] = texture(colortex0, fs_in.uv) + vec4(lit, 0.0) * 1e-6;
}
