#version 330 compatibility
// The End has no sun, moon or sky light for the water model's reflections and highlights.
// OptiFine and Iris load only the programs in world1/ there, so this composite passes the
// scene through with none of the water model's code, and water and other translucent blocks
// (no gbuffers_water here) are drawn as in vanilla.

uniform sampler2D colortex0;

in vec2 screenUv;

/* RENDERTARGETS: 0 */
out vec4 outColor0;

void main() {
    outColor0 = texture(colortex0, screenUv);
}
