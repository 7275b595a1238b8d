#version 120
// The albedo sampler declared under OptiFine's old name `texture` and read as `gtexture` through
// texture(), as Arthiyart/SHORE writes it: Iris names the sampler `gtexture` (its declaration and
// every use that is not a call) and raises the stage to 3.30, where texture() exists.
uniform sampler2D texture;
varying vec2 texcoord;
varying vec4 glcolor;
void main() {
    gl_FragData[0] = texture(gtexture, texcoord) * glcolor;
}
