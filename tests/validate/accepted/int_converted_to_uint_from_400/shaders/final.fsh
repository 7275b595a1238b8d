#version 430 compatibility
// GLSL 4.00 converts int to uint implicitly, in returns (from 4.20) and assignments alike, as
// LordChrom/MagicLightShayder's ordered dither returns a shifted int from a uint function.
uniform sampler2D colortex0;
in vec2 texcoord;
uint bayer2(ivec2 pos) {
    return ((pos.x & 1) << 31) - ((pos.y & 1) << 30);
}
void main() {
    uint threshold = bayer2(ivec2(gl_FragCoord.xy)) + (bayer2(ivec2(gl_FragCoord.xy) >> 1) >> 2);
    uvec2 cell = ivec2(gl_FragCoord.xy) & 3;
    float dither = float(threshold + cell.x) * exp2(-32.0);
    gl_FragData[0] = texture(colortex0, texcoord) + dither / 255.0;
}
