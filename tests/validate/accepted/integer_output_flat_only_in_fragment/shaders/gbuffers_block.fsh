#version 450 compatibility
in flat int entityMark;
void main() { gl_FragData[0] = vec4(float(entityMark)); }
