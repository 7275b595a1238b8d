#version 330 compatibility
// Inputs placed at the generic locations NVIDIA's driver aliases to the legacy position (0),
// colour (3) and texture coordinate (8): OptiFine feeds those arrays, so on NVIDIA these read
// the vertex's data; Mesa leaves them at their current value.
layout(location = 0) in vec4 position;
layout(location = 3) in vec4 vertexColor;
layout(location = 8) in vec4 texCoord;
out vec2 uv;
out vec4 tint;
void main() {
    gl_Position = gl_ModelViewProjectionMatrix * position;
    uv = (gl_TextureMatrix[0] * texCoord).xy;
    tint = vertexColor;
}
