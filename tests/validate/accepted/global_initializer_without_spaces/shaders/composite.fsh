#version 120
// Minified packs write initializers without spaces: `a=exp(d)` runs at the start of main.
uniform float rainStrength;
uniform sampler2D colortex0;
varying vec2 uv;
float dimmed=exp(-rainStrength);
void main() {
    gl_FragColor = texture2D(colortex0, uv) * dimmed;
}
