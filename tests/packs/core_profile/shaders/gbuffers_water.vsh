#version 150
// The 1.17+ core profile: vertex data and matrices by their new names, positions relative to
// the chunk at chunkOffset.
in vec3 vaPosition;
in vec4 vaColor;
in vec2 vaUV0;
in ivec2 vaUV2;
uniform mat4 modelViewMatrix;
uniform mat4 projectionMatrix;
uniform vec3 chunkOffset;
out vec4 color;
out vec4 coords;
void main() {
    gl_Position = projectionMatrix * modelViewMatrix * vec4(vaPosition + chunkOffset, 1.0);
    color = vaColor;
    coords = vec4(vaUV0, vec2(vaUV2) / 256.0);
}
