#version 120
// Terrain casts its colour into shadowcolor0, water a blue tint; output 1 marks water.
varying vec4 color;
varying float water;
void main() {
/* DRAWBUFFERS:01 */
    gl_FragData[0] = mix(color, vec4(0.1, 0.3, 0.9, 1.0), water);
    gl_FragData[1] = vec4(water, 0.0, 0.0, 1.0);
}
