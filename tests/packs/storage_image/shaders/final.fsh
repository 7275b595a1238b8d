#version 430 compatibility
// The image's sampler: custom images are not held, so it reads zero in both renderers.
uniform sampler2D colortex0;
uniform sampler2D markSampler;
in vec2 uv;
void main() {
    gl_FragColor = vec4(texture(colortex0, uv).rgb + texture(markSampler, uv).rgb, 1.0);
}
