#version 120
// Absorption and scattering at 0 (a menu value) make the albedo 0/0: NaN, folded by the
// compiler, which drivers compile.
#define WATER_SCATTERING 0.0 // [0.0 0.5 1.0]
#define WATER_ABSORPTION 0.0 // [0.0 0.5 1.0]
const float extinction = WATER_SCATTERING + WATER_ABSORPTION;
const float albedo = WATER_SCATTERING / extinction;
void main() { gl_FragData[0] = vec4(albedo); }
