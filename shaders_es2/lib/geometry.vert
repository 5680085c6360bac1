// The vertex stage of every geometry pass (G-buffer, lighting, velocity): the same text and the same uniforms, so
// all of them rasterize exactly the same fragments (invariant gl_Position) and the lighting pass can read the AO at
// gl_FragCoord and the velocity pass can depth-test EQUAL-or-nearer against the G-buffer's depth.
//
// Deformation (gpu/GpuScene.h chooses the variant per draw, sized to what the context guarantees):
//   MORPH_TARGETS n (0..4): n morph targets' POSITION deltas in attributes, MORPH_NORMALS 1 their NORMAL deltas too,
//     MORPH_TANGENTS 1 their TANGENT deltas too, scaled by u_morphWeights (glTF 2.0 "Morph Targets": morphing comes
//     before skinning).
//   SKINNING 1: linear blend skinning from a uniform palette of SKIN_PALETTE joints (3 rows of each joint's affine
//     matrix world(joint) * inverseBind(joint)); a mesh with more joints is drawn in pieces that each fit.
//   SKINNING 2: the same matrices read from a float texture (vertex texture fetch), any number of joints.
// Skinned vertices come out in world space, so a skinned draw's model-view is the view matrix alone.
//   PREVIOUS 1 (the velocity pass): also the vertex where the previous frame had it, through the previous frame's
//     pose (u_previousModel, previous palette or weights) and camera (u_previousViewProjection), both unjittered.
//   CPU_DEFORMED 1: the CPU has skinned and morphed the vertex (the fallback); a_previousPosition is its previous
//     position in the same space, a_tangent its deformed tangent.
// VERTEX_COLORS 1: the mesh's COLOR_0 (a_color), passed on to lib/material.glsl, which multiplies the base colour.
// a_texcoord holds TEXCOORD_0 in xy and TEXCOORD_1 in zw; each PBR_TEXTURES slot samples the set the material names.
#ifndef SKINNING
#define SKINNING 0
#endif
#ifndef MORPH_TARGETS
#define MORPH_TARGETS 0
#endif
#ifndef MORPH_NORMALS
#define MORPH_NORMALS 0
#endif
#ifndef PREVIOUS
#define PREVIOUS 0
#endif
#ifndef CPU_DEFORMED
#define CPU_DEFORMED 0
#endif
#ifndef PBR_TEXTURES
#define PBR_TEXTURES 0
#endif
#ifndef MORPH_TANGENTS
#define MORPH_TANGENTS 0
#endif
#ifndef VERTEX_COLORS
#define VERTEX_COLORS 0
#endif

attribute vec3 a_position;
attribute vec3 a_normal;
attribute vec4 a_texcoord;
#if VERTEX_COLORS
attribute vec4 a_color;
varying vec4 v_color;
#endif

// The instance's transforms, one array set by one call per draw (gpu/GpuScene.cpp: on the page each WebGL call costs
// about a microsecond of host time, and two matrices made two): [0..3] the model-view's columns, [4..6].xyz the
// normal matrix's (the inverse transpose of the model-view's upper 3x3).
uniform vec4 u_instanceTransforms[7];
uniform mat4 u_projection;

varying vec3 v_viewPosition;
varying vec3 v_viewNormal;
varying vec2 v_texcoord;
varying vec4 v_clipPosition;  // read by the lighting pass to address the AO texture in highp

#if PBR_TEXTURES
// PBR_TEXTURES 1 (gpu/MaterialKind.h): the tangent frame for the normal texture, and each texture slot's
// coordinates through its KHR_texture_transform (affine in uv, so transforming per vertex is exact):
// u_uvTransforms[2 k], [2 k + 1] are the rows of slot k's 3x3 matrix (base colour, metallic-roughness, normal,
// occlusion, emissive: scene/Scene.h TextureSlot). u_uvSets holds each slot's set as a bit, sum of set_k 2^k (no
// bitwise operators in GLSL ES 1.00: floor and mod read it), one float where five would take five rows.
attribute vec4 a_tangent;
uniform vec3 u_uvTransforms[10];
uniform float u_uvSets;
varying vec4 v_viewTangent;
varying vec4 v_uvMetallicNormal;
varying vec4 v_uvOcclusionEmissive;
vec2 slotUv(int slot, float bit) {
  float second = mod(floor(u_uvSets / bit), 2.0);
  vec3 uv = vec3(mix(a_texcoord.xy, a_texcoord.zw, second), 1.0);
  return vec2(dot(u_uvTransforms[2 * slot], uv), dot(u_uvTransforms[2 * slot + 1], uv));
}
#endif

#if PREVIOUS
uniform mat4 u_unjitteredProjection;    // this frame's projection without the sub-pixel jitter
uniform mat4 u_previousModel;           // the instance's previous world matrix (identity for skinned vertices)
uniform mat4 u_previousViewProjection;  // the previous frame's camera, unjittered
varying vec4 v_currentClip;
varying vec4 v_previousClip;
#if CPU_DEFORMED
attribute vec3 a_previousPosition;
#endif
#endif

#if MORPH_TARGETS > 0
uniform vec4 u_morphWeights;
#if PREVIOUS
uniform vec4 u_previousMorphWeights;
#endif
attribute vec3 a_morphPosition0;
#if MORPH_NORMALS
attribute vec3 a_morphNormal0;
#endif
#if MORPH_TANGENTS
attribute vec3 a_morphTangent0;
#endif
#endif
#if MORPH_TARGETS > 1
attribute vec3 a_morphPosition1;
#if MORPH_NORMALS
attribute vec3 a_morphNormal1;
#endif
#if MORPH_TANGENTS
attribute vec3 a_morphTangent1;
#endif
#endif
#if MORPH_TARGETS > 2
attribute vec3 a_morphPosition2;
#if MORPH_NORMALS
attribute vec3 a_morphNormal2;
#endif
#if MORPH_TANGENTS
attribute vec3 a_morphTangent2;
#endif
#endif
#if MORPH_TARGETS > 3
attribute vec3 a_morphPosition3;
#if MORPH_NORMALS
attribute vec3 a_morphNormal3;
#endif
#if MORPH_TANGENTS
attribute vec3 a_morphTangent3;
#endif
#endif

#if MORPH_TARGETS > 0
vec3 morphPosition(vec4 w) {
  vec3 p = a_position + w.x * a_morphPosition0;
#if MORPH_TARGETS > 1
  p += w.y * a_morphPosition1;
#endif
#if MORPH_TARGETS > 2
  p += w.z * a_morphPosition2;
#endif
#if MORPH_TARGETS > 3
  p += w.w * a_morphPosition3;
#endif
  return p;
}
vec3 morphNormal(vec4 w) {
  vec3 n = a_normal;
#if MORPH_NORMALS
  n += w.x * a_morphNormal0;
#if MORPH_TARGETS > 1
  n += w.y * a_morphNormal1;
#endif
#if MORPH_TARGETS > 2
  n += w.z * a_morphNormal2;
#endif
#if MORPH_TARGETS > 3
  n += w.w * a_morphNormal3;
#endif
#endif
  return n;
}
#if PBR_TEXTURES
vec3 morphTangent(vec4 w) {
  vec3 t = a_tangent.xyz;
#if MORPH_TANGENTS
  t += w.x * a_morphTangent0;
#if MORPH_TARGETS > 1
  t += w.y * a_morphTangent1;
#endif
#if MORPH_TARGETS > 2
  t += w.z * a_morphTangent2;
#endif
#if MORPH_TARGETS > 3
  t += w.w * a_morphTangent3;
#endif
#endif
  return t;
}
#endif
#endif

#if SKINNING
attribute vec4 a_joints;   // palette entries (SKINNING 1) or skin joints (SKINNING 2), as floats
attribute vec4 a_weights;  // summing to 1

// The blended skinning matrix as its three rows: sum_k w_k M(j_k) (linear blend skinning).
struct SkinRows {
  vec4 r0, r1, r2;
};

#if SKINNING == 1
uniform vec4 u_joints[3 * SKIN_PALETTE];
#if PREVIOUS
uniform vec4 u_previousJoints[3 * SKIN_PALETTE];
#endif
SkinRows blendJoints(bool previous) {
  SkinRows s;
  s.r0 = vec4(0.0);
  s.r1 = vec4(0.0);
  s.r2 = vec4(0.0);
  for (int k = 0; k < 4; k++) {
    // GLSL ES 1.00 Appendix A: vertex shaders may index uniform arrays by any integer expression.
    int row = int(a_joints[k] + 0.5) * 3;
    float w = a_weights[k];
#if PREVIOUS
    if (previous) {
      s.r0 += w * u_previousJoints[row];
      s.r1 += w * u_previousJoints[row + 1];
      s.r2 += w * u_previousJoints[row + 2];
    } else
#endif
    {
      s.r0 += w * u_joints[row];
      s.r1 += w * u_joints[row + 1];
      s.r2 += w * u_joints[row + 2];
    }
  }
  return s;
}
#else
uniform highp sampler2D u_jointTexture;  // RGBA float, NEAREST: rows of the current then the previous palette
uniform vec3 u_jointTextureSize;         // width, height, texels per palette (3 x joints)
vec4 jointRow(float texel) {
  float y = floor((texel + 0.5) / u_jointTextureSize.x);
  float x = texel - y * u_jointTextureSize.x;
  return texture2DLod(u_jointTexture, (vec2(x, y) + 0.5) / u_jointTextureSize.xy, 0.0);
}
SkinRows blendJoints(bool previous) {
  SkinRows s;
  s.r0 = vec4(0.0);
  s.r1 = vec4(0.0);
  s.r2 = vec4(0.0);
  float base = previous ? u_jointTextureSize.z : 0.0;
  for (int k = 0; k < 4; k++) {
    float texel = base + floor(a_joints[k] + 0.5) * 3.0;
    float w = a_weights[k];
    s.r0 += w * jointRow(texel);
    s.r1 += w * jointRow(texel + 1.0);
    s.r2 += w * jointRow(texel + 2.0);
  }
  return s;
}
#endif
vec3 skinPoint(SkinRows s, vec3 p) {
  vec4 h = vec4(p, 1.0);
  return vec3(dot(s.r0, h), dot(s.r1, h), dot(s.r2, h));
}
// The blended matrix's linear part, as the CPU mirror (scene/Animation.h: posedMesh) does.
vec3 skinVector(SkinRows s, vec3 v) { return vec3(dot(s.r0.xyz, v), dot(s.r1.xyz, v), dot(s.r2.xyz, v)); }
#endif

invariant gl_Position;

void main() {
#if MORPH_TARGETS > 0
  vec3 position = morphPosition(u_morphWeights);
  vec3 normal = morphNormal(u_morphWeights);
#else
  vec3 position = a_position;
  vec3 normal = a_normal;
#endif
#if PBR_TEXTURES && MORPH_TARGETS > 0
  vec3 tangent = morphTangent(u_morphWeights);
#elif PBR_TEXTURES
  vec3 tangent = a_tangent.xyz;
#endif
#if PBR_TEXTURES
  float handedness = a_tangent.w;
#endif
#if SKINNING
  SkinRows skin = blendJoints(false);
  position = skinPoint(skin, position);
  normal = skinVector(skin, normal);
#if PBR_TEXTURES
  tangent = skinVector(skin, tangent);
  // A mirroring joint (the blended matrix's determinant negative) reverses the bitangent's cross product, as a
  // mirrored node does (below): w turns with it (the CPU mirror: scene/Animation.h posedMesh).
  if (dot(skin.r0.xyz, cross(skin.r1.xyz, skin.r2.xyz)) < 0.0) handedness = -handedness;
#endif
#endif
  mat4 modelView =
      mat4(u_instanceTransforms[0], u_instanceTransforms[1], u_instanceTransforms[2], u_instanceTransforms[3]);
  vec4 viewPosition = modelView * vec4(position, 1.0);
  v_viewPosition = viewPosition.xyz;
  v_viewNormal =
      mat3(u_instanceTransforms[4].xyz, u_instanceTransforms[5].xyz, u_instanceTransforms[6].xyz) * normal;
#if VERTEX_COLORS
  v_color = a_color;
#endif
#if PBR_TEXTURES
  v_texcoord = slotUv(0, 1.0);
  v_uvMetallicNormal = vec4(slotUv(1, 2.0), slotUv(2, 4.0));
  v_uvOcclusionEmissive = vec4(slotUv(3, 8.0), slotUv(4, 16.0));
  // The tangent is a direction on the surface: the model-view's linear part (not the normal matrix) carries it. A
  // mirroring transform (a negative determinant: a node scaled by -1 along an axis) reverses the cross product the
  // fragment stage makes the bitangent from (glTF 2.0: bitangent = cross(normal, tangent.xyz) * w), so w turns with
  // it and the normal texture's green still follows the texture's v.
  mat3 linear = mat3(modelView[0].xyz, modelView[1].xyz, modelView[2].xyz);
  if (dot(linear[0], cross(linear[1], linear[2])) < 0.0) handedness = -handedness;
  v_viewTangent = vec4(linear * tangent, handedness);
#else
  v_texcoord = a_texcoord.xy;
#endif
  gl_Position = u_projection * viewPosition;
  v_clipPosition = gl_Position;

#if PREVIOUS
  v_currentClip = u_unjitteredProjection * viewPosition;
#if CPU_DEFORMED
  vec3 previous = a_previousPosition;
#elif MORPH_TARGETS > 0
  vec3 previous = morphPosition(u_previousMorphWeights);
#else
  vec3 previous = a_position;
#endif
#if SKINNING
  previous = skinPoint(blendJoints(true), previous);
#endif
  v_previousClip = u_previousViewProjection * (u_previousModel * vec4(previous, 1.0));
#endif
}
