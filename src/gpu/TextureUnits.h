#pragma once
// The texture units of the scene's draws and the lighting pass, in one table. GLES 2 guarantees 8 units to the
// fragment stage and 8 in all (GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS), none to the vertex stage. The forward lighting
// of a material with every texture samples eight in its fragment stage (the base colour, the AO, the four PBR
// textures, the environment's two textures): all eight that GLES 2 guarantees, so the joint texture of vertex
// skinning needs a ninth unit, which only a context with more than 8 combined units has (GpuScene then takes the
// uniform palette). The full-screen passes bind their own inputs from unit 0 and restore nothing but unit 0 as active.
#include "gl/GlCaps.h"

namespace obscura::TextureUnits {

// The material's base colour texture (the G-buffer in the deferred lighting, which reads the G-buffer pass's base
// colour on kPbr[0]).
inline constexpr int kBaseColor = 0;
inline constexpr int kAo = 1;  // the lighting pass's AO
// The AO's depth peel (effects/ao/DepthPeelPass.h) reads the G-buffer on the AO's unit, free in that pass.
inline constexpr int kPeeledGBuffer = kAo;
// A PBR_TEXTURES material's metallic-roughness, normal, occlusion and emissive textures.
inline constexpr int kPbr[4] = {2, 3, 5, 6};
inline constexpr int kJoints = 4;  // the vertex stage's joint texture (GpuScene)
inline constexpr int kEnvironment = 7;
// The background's cube map (environment/Environment.h: skyCubeFaces), in the lighting's full-screen forms alone
// (deferred, and the forward forms' background draw), which read no material texture: a PBR unit is free there. The
// lighting unbinds it after its pass (the baseline state holds no cube map).
inline constexpr int kSky = kPbr[1];
// Units 0 .. 7 are GLES 2's; a ninth exists where the combined limit is larger.
inline constexpr int kGles2Units = 8;

// The joint texture may be bound only where a ninth unit exists: the fragment stage may use all eight others.
inline bool jointTextureFits(const gl::GlCaps& caps) {
  return caps.maxVertexTextureImageUnits > 0 && caps.maxCombinedTextureImageUnits > kGles2Units;
}
// The environment's filtered texture (its rough levels and the BRDF table): the ninth unit where the context has one,
// else the joints' unit, which is then free (jointTextureFits is false).
inline int environmentFiltered(const gl::GlCaps& caps) {
  return caps.maxCombinedTextureImageUnits > kGles2Units ? kGles2Units : kJoints;
}

// The unit the lighting leaves to the per-pixel stages fused into it (frame/Stage.h: grading's LUT): the tenth, where
// the fragment stage has one (GLES 2 guarantees 8; desktop GL, WebGL on SwiftShader and most phones offer 16). Without
// it such a stage runs in a stage pass of its own.
inline constexpr int kStages = kGles2Units + 1;
inline int stageUnits(const gl::GlCaps& caps) {
  return caps.maxTextureImageUnits > kStages && caps.maxCombinedTextureImageUnits > kStages ? 1 : 0;
}

}  // namespace obscura::TextureUnits
