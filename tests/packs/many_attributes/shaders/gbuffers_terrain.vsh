#version 150 compatibility
// Nine vertex inputs of the pack's own, as 1.17+ packs declare the core profile's attributes
// beside the older ones: more than OpenGL's 16 attribute locations hold after the eight the
// legacy inputs keep. Each one read, so that none is dropped.
in vec4 mc_Entity;
in vec4 at_tangent;
in vec4 mc_midTexCoord;
in vec3 vaPosition;
in vec4 vaColor;
in vec3 vaNormal;
in vec2 vaUV0;
in ivec2 vaUV2;
in vec4 at_midBlock;
out vec4 colour;
void main() {
    gl_Position = gl_ModelViewProjectionMatrix * vec4(vaPosition, 1.0);
    float nonzero = step(0.0, mc_Entity.x + at_tangent.w + mc_midTexCoord.x + vaNormal.y + vaUV0.x + float(vaUV2.x) + at_midBlock.x);
    colour = vec4(vaColor.rgb * nonzero, 1.0);
}
