#version 100
// GLSL ES 1.00: NVIDIA compiles it as desktop GLSL; Mesa wants a default float precision
// before `vec2` and will not link it with a desktop vertex stage. It writes no output, only
// discards: the loader's alpha test has nothing to read, and no water is drawn.
varying vec2 uv;
void main() {
    if (uv.x < 2.0) discard;
}
