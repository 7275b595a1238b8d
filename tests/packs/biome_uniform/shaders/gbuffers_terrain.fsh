#version 120
// Green where the biome uniforms say plains; red otherwise.
uniform float inPlains;
uniform float temperature;
uniform float rainfall;
void main() {
    gl_FragData[0] = vec4(1.0 - inPlains, inPlains, temperature * rainfall, 1.0);
}
