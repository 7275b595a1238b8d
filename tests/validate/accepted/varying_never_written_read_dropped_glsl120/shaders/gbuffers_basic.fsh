#version 120
// lightColor is read only where the value goes nowhere: into a parameter the function ignores,
// and into a variable nothing reads. Mesa's optimiser drops both reads and links the program.
varying vec3 lightColor;
varying vec4 color;
vec3 fogged(vec3 albedo, vec3 light) {
    return albedo * 0.9;
}
void main() {
    vec3 unused = lightColor * 2.0;
    gl_FragData[0] = vec4(fogged(color.rgb, lightColor), color.a);
}
