#version 120
// Green where the biome uniforms say plains; red otherwise. Black where the camera moved since
// the last frame, which the scenes' still camera never does (a `uniform bool`).
uniform float inPlains;
uniform float temperature;
uniform float rainfall;
uniform bool cameraStill;
// Uniforms no loader sets keep their initializers (a pack's own settings, as
// Makenbo/pretty-aesthetic-minecraft-shader picks its tone mapping's gamut).
uniform float strength = 1.0;
uniform ivec2 levels = ivec2(2, 4);
void main() {
    float level = float(levels.y) / float(levels.x * 2);
    gl_FragData[0] = vec4(1.0 - inPlains, inPlains, temperature * rainfall, 1.0) * float(cameraStill) * strength * level;
}
