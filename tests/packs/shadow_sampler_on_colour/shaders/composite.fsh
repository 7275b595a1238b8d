#version 120
// A shadow colour buffer read through a shadow sampler, as released packs do: OpenGL leaves the
// result undefined and the loaders bind the buffer as it is; wgpu cannot bind a colour texture
// to a comparison. The scene is kept whatever the lookup returns.
uniform sampler2D colortex0;
uniform sampler2DShadow shadowcolor0;
varying vec2 uv;
void main() {
    float shadow = shadow2D(shadowcolor0, vec3(uv, 0.5)).r;
    gl_FragData[0] = vec4(texture2D(colortex0, uv).rgb + 0.0 * shadow, 1.0);
}
