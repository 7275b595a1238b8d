#version 120
flat varying vec3 faceColour;
void main() {
    gl_FragData[0] = vec4(faceColour, 1.0);
}
