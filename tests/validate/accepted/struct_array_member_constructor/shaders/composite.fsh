#version 120
// Structs with an array member, built from array constructors in a constant and in a function.
varying vec2 uv;
struct Layer { float width; float scale; };
struct Profile { Layer layers[2]; float weights[3]; };
struct Atmosphere { vec3 tint; Profile air; };
const Atmosphere SKY = Atmosphere(vec3(1.0), Profile(Layer[2](Layer(0.0, 1.0), Layer(2.0, 3.0)), float[3](0.25, 0.5, 0.25)));
void main() {
	Profile local = Profile(Layer[2](Layer(uv.x, 1.0), Layer(2.0, uv.y)), float[3](uv.x, 0.5, uv.y));
	gl_FragData[0] = vec4(SKY.tint * SKY.air.layers[1].scale * local.layers[0].width * local.weights[2], 1.0);
}
