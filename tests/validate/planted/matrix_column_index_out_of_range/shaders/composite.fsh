#version 330 compatibility
// One dimension's light colours are two columns; code shared with a dimension that has three
// reads the third.
flat in mat2x3 lightColor;
uniform float sunAngle;
void main() {
    vec3 bounce = (sunAngle < 0.5 ? lightColor[0] : lightColor[2]) * 0.04;
    gl_FragData[0] = vec4(bounce, 1.0);
}
