// The vertex stage of both geometry passes (G-buffer and lighting): the same text and the same uniforms, so both
// rasterize exactly the same fragments and the lighting pass can read the AO at gl_FragCoord.
attribute vec3 a_position;
attribute vec3 a_normal;
attribute vec2 a_texcoord;

uniform mat4 u_modelView;
uniform mat4 u_projection;
uniform mat3 u_normalMatrix;  // inverse transpose of the model-view's upper 3x3

varying vec3 v_viewPosition;
varying vec3 v_viewNormal;
varying vec2 v_texcoord;
varying vec4 v_clipPosition;  // read by the lighting pass to address the AO texture in highp

invariant gl_Position;

void main() {
  vec4 viewPosition = u_modelView * vec4(a_position, 1.0);
  v_viewPosition = viewPosition.xyz;
  v_viewNormal = u_normalMatrix * a_normal;
  v_texcoord = a_texcoord;
  gl_Position = u_projection * viewPosition;
  v_clipPosition = gl_Position;
}
