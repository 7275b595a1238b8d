#version 420 compatibility
// A global initialised from a call, an int vector converted to the declared vec2 through a
// swizzle of the call's result (BruceKnowsHow/Octray's atlas size): GLSL converts it implicitly.
uniform sampler2D depthtex1;
struct Atlas { ivec2 size; };
const Atlas atlas = Atlas(ivec2(16, 8));
vec2 atlasSize = textureSize(depthtex1, 0).xy;
vec2 tileSize = atlas.size.yx;
in vec2 uv;
void main() {
    gl_FragData[0] = vec4(uv * atlasSize / tileSize, 0.0, 1.0);
}
