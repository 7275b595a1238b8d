#version 120
// A struct instance declared without a value, a member of it read before anything writes it,
// as SEUS's composites read a sky member they never set: undefined in GLSL (Mesa's can be NaN),
// 0 in wgpu.
uniform sampler2D colortex0;
varying vec2 uv;
struct Sky {
    vec3 albedo;
    vec3 glow;
    float weights[2];
};
struct Surface {
    Sky sky;
    float depth;
} surface;
void main() {
    surface.sky.albedo = texture2D(colortex0, uv).rgb;
    vec3 sky = surface.sky.albedo + surface.sky.glow * (1.0 + surface.sky.weights[1]);
    gl_FragData[0] = vec4(pow(sky, vec3(1.0 / 2.2)), 1.0);
}
