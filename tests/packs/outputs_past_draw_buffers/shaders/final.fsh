#version 330 compatibility
// One header declares ten outputs for every program (as DrDesten/Groundwork's does); this one
// writes the first. Locations 8 and 9 have no draw buffer: the loaders drop them.
layout(location = 0) out vec4 FD0;
layout(location = 1) out vec4 FD1;
layout(location = 8) out vec4 FD8;
layout(location = 9) out vec4 FD9;
in vec2 uv;
/* RENDERTARGETS: 0 */
void main() {
    FD0 = vec4(0.0, 0.0, 1.0, 1.0);
}
