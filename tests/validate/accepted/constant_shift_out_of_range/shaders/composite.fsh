#version 440 compatibility
// Bits shifted out of an int or uint constant are dropped.
const int signBit = 1 << 31;
const uint topByte = 0xFFu << 28;
in vec2 uv;
void main() {
	int bits = floatBitsToInt(uv.x) & ~signBit;
	int mask = 3 << 30;
	gl_FragData[0] = vec4(intBitsToFloat(bits), float(topByte >> 28u), float(mask), 1.0);
}
