#version 430 compatibility
// Draws what the terrain left in the buffer object over the whole screen.
layout(std430, binding = 0) readonly buffer Shared {
    vec4 colour;
} shared_data;
/* RENDERTARGETS: 0 */
layout(location = 0) out vec4 result;
void main() {
    result = shared_data.colour;
}
