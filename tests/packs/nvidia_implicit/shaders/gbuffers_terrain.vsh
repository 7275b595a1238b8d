#version 330 compatibility
// Inputs placed at the generic locations NVIDIA's driver aliases to the legacy position (0),
// colour (3) and texture coordinate (8): OptiFine feeds those arrays, so on NVIDIA these read
// the vertex's data; Mesa leaves them at their current value.
layout(location = 0) in vec4 position;
layout(location = 3) in vec4 vertexColor;
layout(location = 8) in vec4 texCoord;
out vec2 uv;
out vec4 tint;
// Only named, never called, as in packs whose stages share one library: a bias where there is no level
// to bias, which NVIDIA takes as the level.
uniform sampler2D gtexture;
vec4 blurredColour(vec2 at) {
    return texture2D(gtexture, at, 2.0);
}
void main() {
    gl_Position = gl_ModelViewProjectionMatrix * position;
    uv = (gl_TextureMatrix[0] * texCoord).xy;
    tint = vertexColor;
    // A function named with no call: NVIDIA ignores the statement.
    blurredColour;
}
