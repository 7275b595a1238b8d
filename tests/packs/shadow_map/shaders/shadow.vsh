#version 120
// The shadow pass: positions under shadowModelView and shadowProjection (the legacy
// matrices there), the block id telling water from terrain.
attribute vec4 mc_Entity;
varying vec4 color;
varying float water;
void main() {
    gl_Position = ftransform();
    color = gl_Color;
    water = float(mc_Entity.x == 8.0 || mc_Entity.x == 9.0);
}
