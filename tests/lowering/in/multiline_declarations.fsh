#version 120
uniform sampler2D colortex0,
                  colortex1;
varying vec2 texcoord,
             lmcoord;
void main() {
	gl_FragData[0] = texture2D(colortex0, texcoord) + texture2D(colortex1, lmcoord);
	gl_FragData[1] = vec4(texcoord, lmcoord);
}
