#version 130
#define LIGHTS 256 //[0 256]
#define STRENGTH 1.0 //[0.5 1.0]
// A function-like macro named like a swizzle: Mesa's preprocessor reads `(colour.a)` below as
// an unfinished call of it; Iris's preprocessor leaves the driver no macro to misread.
#define a(x) (x)
uniform sampler2D colortex0;
flat varying vec3 tint;
varying vec2 texcoord;
// inverse() came with GLSL 1.40: this stage compiles because Iris raises it to 3.30.
mat2 undone(mat2 m) { return inverse(m); }
void main() {
    vec4 colour = texture2D(colortex0, texcoord);
    // A float in #if: Iris's preprocessor reads its integer part; Mesa's refuses it.
#if STRENGTH > 0
    colour.rgb *= tint;
#endif
#ifdef IRIS_FEATURE_CUSTOM_IMAGES
    colour.a = (colour.a);
#else
    colour = vec4(1.0, 0.0, 1.0, 1.0);
#endif
    colour.rg = undone(mat2(1.0)) * colour.rg;
    gl_FragData[0] = colour;
}
