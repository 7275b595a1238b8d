#version 120
// The loader says which kind of draw this is: blue carries renderStage
// (MC_RENDER_STAGE_TERRAIN_SOLID); alpha stays 1, clear of the loader's alpha test.
uniform int renderStage;
varying vec4 color;
void main() {
    gl_FragData[0] = vec4(color.rg, float(renderStage) / 255.0, 1.0);
}
