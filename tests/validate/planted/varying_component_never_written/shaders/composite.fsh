#version 120
uniform sampler2D gcolor;
varying vec3 texcoord;
void main() {
    vec4 colour = texture2D(gcolor, texcoord.st);
    gl_FragData[0] = colour * min(texcoord.b + 0.4, 1.0);
}
