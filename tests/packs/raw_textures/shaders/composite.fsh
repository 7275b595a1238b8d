#version 120
// The texel centres read: (1, 0, 1) of the volume, (200, 100, 50, 255); texel 2 of the line,
// whose green is 0.2. Without a .mcmeta both filter nearest. colortex7's flat normal map has
// a blue of 1.
uniform sampler3D colortex5;
uniform sampler1D colortex6;
uniform sampler2D colortex7;
void main() {
/* DRAWBUFFERS:0 */
    vec4 corner = texture3D(colortex5, vec3(0.75, 0.25, 0.75));
    float line = texture1D(colortex6, 0.625).g * texture2D(colortex7, vec2(0.5)).b;
    gl_FragData[0] = vec4(corner.rg, line, 1.0);
}
