// The vertex stage of the programs that draw as the game does (lib/vanilla.glsl). The
// including program declares the outputs texUv, lightUv, tint and viewDistance.

void main() {
    vec4 viewPos = gl_ModelViewMatrix * gl_Vertex;
    gl_Position = gl_ProjectionMatrix * viewPos;
    texUv = (gl_TextureMatrix[0] * gl_MultiTexCoord0).xy;
    lightUv = (gl_TextureMatrix[1] * gl_MultiTexCoord1).xy;
    tint = gl_Color;
    viewDistance = length(viewPos.xyz);
}
