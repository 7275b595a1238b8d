#version 120
// `||` of two bvec2s, which NVIDIA applies to each component and GLSL refuses
// (saadam1n/MinecraftShaders' chromatic aberration).
varying vec2 uv;
void main() {
    bvec2 outside = lessThan(uv, vec2(0.25)) || greaterThan(uv, vec2(0.75));
    gl_FragData[0] = vec4(any(outside) ? 1.0 : 0.0);
}
