#version 430 compatibility
// Every terrain fragment stores the same blue into the buffer object, which outlives the draw.
layout(std430, binding = 0) buffer Shared {
    vec4 colour;
} shared_data;
void main() {
    shared_data.colour = vec4(0.0, 0.0, 1.0, 1.0);
    gl_FragData[0] = vec4(0.0, 1.0, 0.0, 1.0);
}
