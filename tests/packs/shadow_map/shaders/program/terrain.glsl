// Both stages of gbuffers_terrain in one file, each under its own #ifdef and the file ending on
// #endif, as Complementary writes its programs: the loader's alpha test must wrap the main the
// driver compiles. The tangent and the sprite centre are the game's terrain vertex data.
#ifdef FSH
varying vec4 color;
varying vec4 tangent;
varying vec2 spriteCentre;
void main() {
/* DRAWBUFFERS:01 */
    gl_FragData[0] = color;
    gl_FragData[1] = vec4(tangent.xyz * 0.5 + 0.5, tangent.w * 0.25 + 0.5 + spriteCentre.x * 0.1);
}
#endif

#ifdef VSH
attribute vec4 at_tangent;
attribute vec4 mc_midTexCoord;
varying vec4 color;
varying vec4 tangent;
varying vec2 spriteCentre;
void main() {
    gl_Position = ftransform();
    color = gl_Color;
    tangent = at_tangent;
    spriteCentre = mc_midTexCoord.st;
}
#endif
