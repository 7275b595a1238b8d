#version 120
// The game's fog as OptiFine and Iris give it in uniforms, against the legacy gl_Fog state:
// red is fogStart and green fogEnd, both over far; blue is 1 where they agree with gl_Fog.
uniform float fogStart;
uniform float fogEnd;
uniform float far;
void main() {
    float agrees = float(abs(fogStart - gl_Fog.start) < 0.001 && abs(fogEnd - gl_Fog.end) < 0.001);
    gl_FragData[0] = vec4(fogStart / far, fogEnd / far, agrees, 1.0);
}
