#version 430 compatibility
// A storage image, which only OpenGL binds, beside samplers of four other kinds, each of which
// must sit on a texture unit of its own; nothing the harness makes is bound to them: zero.
layout(rgba8) uniform writeonly image2D marks;
uniform sampler2D colortex0;
uniform sampler3D volume;
uniform usampler2DArray layers;
uniform samplerCube sky;
uniform usampler1D palette;
in vec2 uv;
/* RENDERTARGETS: 0 */
layout(location = 0) out vec4 colour;
void main() {
    imageStore(marks, ivec2(gl_FragCoord.xy) % 16, vec4(1.0));
    vec3 zero = texture(volume, vec3(0.5)).rgb + vec3(texelFetch(layers, ivec3(0), 0).rgb) + texture(sky, vec3(0.0, 1.0, 0.0)).rgb + vec3(texelFetch(palette, 0, 0).rgb);
    colour = vec4(texture(colortex0, uv).rgb + zero, 1.0);
}
