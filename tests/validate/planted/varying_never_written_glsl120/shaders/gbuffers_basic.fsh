#version 120
varying vec3 lightColor;
varying vec4 color;
vec3 lit(vec3 albedo, vec3 light) {
    return albedo * light;
}
void main() {
    gl_FragData[0] = vec4(lit(color.rgb, lightColor), color.a);
}
