#version 120
// Written as a pack made on Windows with NVIDIA's driver is: an include whose name differs from
// the file's in case, and `flat varying` in a stage whose `switch` needs GLSL 1.30.
#include "/lib/Shading.glsl"
flat varying vec3 faceColour;
uniform int renderStage;
void main() {
    switch (renderStage) {
        default: faceColour = shade(gl_Normal);
    }
    gl_Position = ftransform();
}
