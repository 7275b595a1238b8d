#version 330 compatibility
// Values NVIDIA converts and GLSL does not: a vec4 stored in a float (its first component) and
// a uint returned from a float function. `unused` is declared and never written (undefined: both
// renderers leave its buffer as it was).
uniform sampler2D gtexture;
in vec2 uv;
in vec4 tint;
layout(location = 0) out vec4 albedo;
layout(location = 1) out vec4 unused;
float steps(uint count) {
    return count / 4u;
}
void main() {
    float alpha = texture(gtexture, uv);
    albedo = vec4(texture(gtexture, uv).rgb * tint.rgb * (0.5 + 0.1 * steps(5u)), alpha);
}
