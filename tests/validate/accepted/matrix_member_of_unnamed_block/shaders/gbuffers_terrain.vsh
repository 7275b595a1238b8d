#version 430 compatibility
// A matrix member of an interface block without an instance name, used by its own name (found
// in a released pack's gbuffers programs; Mesa links it, naga takes no matrix as a stage output).
out VertexData {
    vec2 texcoord;
    flat mat3 tbn;
    flat vec3 lightDir;
};
void main() {
    gl_Position = ftransform();
    texcoord = gl_MultiTexCoord0.xy;
    tbn = mat3(gl_NormalMatrix[0], gl_NormalMatrix[1], gl_Normal);
    lightDir = vec3(0.0, 1.0, 0.0);
}
