#version 120
// Green where the biome uniforms say plains; red otherwise. Black where the camera moved since
// the last frame, which the scenes' still camera never does (a `uniform bool`).
uniform float inPlains;
uniform float temperature;
uniform float rainfall;
uniform bool cameraStill;
void main() {
    gl_FragData[0] = vec4(1.0 - inPlains, inPlains, temperature * rainfall, 1.0) * float(cameraStill);
}
