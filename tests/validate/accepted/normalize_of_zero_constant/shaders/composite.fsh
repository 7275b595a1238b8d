#version 400 compatibility
// Every colour multiplier at 0 (menu values) makes the coefficient a zero vector; its
// normalize() is NaN, which drivers fold or leave to run time and compile.
#define RAYLEIGH_R 0.00 // [0.00 0.50 1.00]
#define RAYLEIGH_G 0.00 // [0.00 0.50 1.00]
#define RAYLEIGH_B 0.00 // [0.00 0.50 1.00]
const vec3 rayleighCoeff = vec3(5.8e-6, 1.35e-5, 3.31e-5) * vec3(RAYLEIGH_R, RAYLEIGH_G, RAYLEIGH_B);
uniform sampler2D colortex0;
in vec2 uv;
void main() {
    vec3 scattering = texture(colortex0, uv).rgb * normalize(rayleighCoeff);
    gl_FragData[0] = vec4(scattering, 1.0);
}
