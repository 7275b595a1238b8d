#version 120
varying vec3 lightColors[2];
varying float zfog;
varying vec4 color;
void main() {
	gl_Position = ftransform();
	lightColors[0] = vec3(1.0);
	lightColors[1] = vec3(0.5);
	zfog = 0.0;
	color = gl_Color * gl_SecondaryColor + gl_MultiTexCoord4 * gl_FogCoord;
	gl_FrontSecondaryColor = vec4(0.0);
}
