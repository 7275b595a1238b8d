#version 430 compatibility
// A matrix member of an interface block with an instance name (HyperCol/Ovizros_Simple_Shader
// passes its matrices to a geometry stage so), written whole and by column.
out Transforms {
    vec2 uv;
    mat4 modelView;
    mat3 basis;
} vs_out;
void main() {
    gl_Position = ftransform();
    vs_out.uv = gl_MultiTexCoord0.xy;
    vs_out.modelView = gl_ModelViewMatrix;
    vs_out.basis = mat3(1.0);
    vs_out.basis[2] = gl_Normal;
}
