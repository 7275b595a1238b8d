#version 430 compatibility
in VertexData {
    vec2 texcoord;
    flat mat3 tbn;
    flat vec3 lightDir;
};
uniform sampler2D gtexture;
/* RENDERTARGETS: 0 */
layout(location = 0) out vec4 colorOut;
void main() {
    vec3 normal = tbn * vec3(0.0, 0.0, 1.0);
    colorOut = texture(gtexture, texcoord) * max(dot(normal, lightDir), 0.2);
}
