#version 120
// The tangent and the sprite centre the game gives terrain vertices (normal mapping).
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
