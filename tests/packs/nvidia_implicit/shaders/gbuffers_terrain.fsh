#version 330 compatibility
// What NVIDIA takes and GLSL does not: a vec4 stored in a float (its first component), a uint
// returned from a float function, a `const` local from a parameter (read-only), a lookup offset
// that is not a constant, a vector compared with a scalar (made a vector), and a `mix` of vectors
// with one bool picking every component. `unused` is declared and never written (undefined:
// both renderers leave its buffer as it was).
uniform sampler2D gtexture;
in vec2 uv;
in vec4 tint;
layout(location = 0) out vec4 albedo;
layout(location = 1) out vec4 unused;
float steps(uint count) {
    return count / 4u;
}
float dimmed(float light) {
    const float halfLight = light * 0.5;
    return halfLight;
}
void main() {
    float alpha = texture(gtexture, uv);
    ivec2 neighbour = ivec2(int(tint.r * 2.0), 0);
    vec3 beside = textureOffset(gtexture, uv, neighbour).rgb;
    float lit = int(tint.a * 2.0) >= 0 && tint.rg != 0 ? 1.0 : 0.5;
    lit *= sign(tint.rgb - 0.5) == sign(uv.x - 2.0) ? 0.75 : 1.0;
    lit *= any(lessThan(uv, vec2(-1.0)) || greaterThan(uv, vec2(2.0))) ? 0.5 : 1.0;
    lit *= mix(vec3(0.5), vec3(1.0), tint.b > 0.25).g;
    albedo = vec4(mix(texture(gtexture, uv).rgb, beside, 0.5) * tint.rgb * lit * dimmed(2.0) * (0.5 + 0.1 * steps(5u)), alpha);
}
