#version 330 compatibility
// Blocks match by block name; the instance names may differ.
uniform sampler2D gtexture;
in vec2 uv;
in Material {
    flat int kind;
    vec3 normal;
} surface;
in Lighting {
    vec2 lm;
};
layout(location = 0) out vec4 outColor0;
void main() {
    vec4 albedo = texture(gtexture, uv);
    float shade = surface.kind == 1 ? 0.5 : dot(normalize(surface.normal), vec3(0.0, 1.0, 0.0)) * 0.5 + 0.5;
    outColor0 = albedo * shade * lm.y;
}
