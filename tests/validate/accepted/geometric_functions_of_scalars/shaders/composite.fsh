#version 120
// The geometric functions take any genType, float included (a GGX term squares a roughness
// with dot), beside their vector forms in the same stage.
uniform sampler2D colortex0;
varying vec2 texcoord;
void main() {
    float roughness = texcoord.x;
    float squared = dot(roughness, roughness);
    float length2 = dot(texcoord, texcoord) + dot(vec3(squared), vec3(1.0)) + normalize(roughness - 0.5);
    length2 += reflect(roughness, 1.0) + refract(roughness, 1.0, 0.75) + faceforward(1.0, roughness, -1.0);
    length2 += length(normalize(texcoord)) + reflect(vec3(1.0), vec3(0.0, 1.0, 0.0)).y;
/* DRAWBUFFERS:0 */
    gl_FragData[0] = texture2D(colortex0, texcoord) * length2;
}
