#version 330 compatibility
// A function returning a matrix whose end is reachable without a `return` (the loop's
// `return` is its only one): the value there is undefined, and drivers compile it.
uniform sampler2D colortex0;
in vec2 uv;
mat2x3 gatherPair(vec2 at) {
    for (int i = 0; i < 4; i++) {
        vec3 a = texture(colortex0, at + float(i) * 0.01).rgb;
        if (a.r > 0.5) return mat2x3(a, a * 0.5);
    }
}
void main() {
    mat2x3 pair = gatherPair(uv);
    gl_FragData[0] = vec4(pair[0] + pair[1], 1.0);
}
