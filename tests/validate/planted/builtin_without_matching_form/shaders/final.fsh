#version 120
uniform sampler2D colortex0;
uniform float rainStrength;
varying vec2 uv;
void main() {
    vec3 color = texture2D(colortex0, uv).rgb;
    // mix() takes a third argument: how much of the second to blend in.
    color = mix(color, vec3(0.5));
    gl_FragColor = vec4(color, 1.0);
}
