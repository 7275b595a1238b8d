#version 400 compatibility
struct Fog { vec3 color; float density; mat2 swirl; };
flat in Fog fog;
in vec2 uv;
uniform sampler2D colortex0;

/* RENDERTARGETS: 0 */
layout(location = 0) out vec4 color;

void main() {
    // A vector made from a bool: 1.0 in every component where the comparison holds.
    vec3 inside = vec3(length(uv - 0.5) < 0.25);
    color = vec4(mix(texture(colortex0, uv).rgb, fog.color, inside * fog.density), 1.0);
}
