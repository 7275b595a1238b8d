// The vertex stage of every deferred, composite and final program of this pack: the full-screen quad.
varying vec2 texcoord;
void main() {
    gl_Position = ftransform();
    texcoord = gl_MultiTexCoord0.xy;
}
