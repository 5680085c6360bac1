// Temporal antialiasing (src/effects/taa/TaaEffect.h): three draws of one pass, picked by TAA_STAGE.
//   0 resolve: this frame's jittered HDR colour blended with the reprojected history (Karis 2014, "High quality
//     temporal supersampling"), written into the history target (lib/hdr.glsl's encoding: the measured choice,
//     TaaEffect.h). The history is fetched at the position the velocity of the nearest surface in the 3x3
//     neighbourhood says it had, rejected where the previous frame's depth there lies outside the 3x3's depth range
//     moved by the camera's motion (disocclusion), and clipped in YCoCg towards the neighbourhood's mean onto the
//     box mean +- gamma sigma (Salvi's variance clipping). Everything is averaged in Karis' reversible tone-mapped
//     space (taa/taa.glsl).
//   1 output: the resolved colour into "scene-color", with optional sharpening (TAA_SHARPEN: an unsharp mask of the
//     four neighbours, in the tone-mapped space, so that the history itself is never sharpened again).
//   2 depth: the G-buffer (16-bit linear depth in BA) copied into the depth history, next frame's "previous depth".
#include "lib/precision.glsl"
#include "lib/hdr.glsl"
#include "taa/taa.glsl"

varying vec2 v_uv;

#if TAA_STAGE == 0
#include "lib/reconstruct.glsl"
uniform sampler2D u_color;            // "scene-color", HDR-encoded, NEAREST
uniform sampler2D u_velocity;         // uv units, unjittered (lib/packing.glsl)
uniform sampler2D u_gbuffer;          // this frame's linear depth in BA
uniform sampler2D u_history;          // last frame's resolve, HDR-encoded, NEAREST (filtered here after decoding)
uniform sampler2D u_previousGbuffer;  // last frame's G-buffer (stage 2's copy)
uniform vec2 u_texel;                 // 1 / size
uniform vec2 u_size;
uniform float u_feedback;             // the history's weight; 0: no history this frame
uniform float u_gamma;                // variance clipping's box half-size in standard deviations
uniform mat4 u_viewToPreviousView;    // previous view x inverse(view): where a still point was seen last frame
varying vec3 v_farRay;

vec3 fetchWeighted(sampler2D target, vec2 uv) { return taaToneWeight(taaToYCoCg(decodeHdr(texture2D(target, uv)))); }

float viewDistance(float code) { return u_farPlane * (code * (1.0 / 65535.0) * u_depthToRay.x + u_depthToRay.y); }

void main() {
  vec3 sum = vec3(0.0), sumSquares = vec3(0.0), center = vec3(0.0);
  float codes[9];
  float nearestCode = 65536.0;
  vec2 nearestOffset = vec2(0.0);
  for (int i = 0; i < 9; i++) {
    float row = floor(float(i) / 3.0);
    vec2 offset = vec2(float(i) - 3.0 * row - 1.0, row - 1.0);
    vec2 uv = v_uv + offset * u_texel;
    vec3 c = fetchWeighted(u_color, uv);
    sum += c;
    sumSquares += c * c;
    if (i == 4) center = c;
    float code = unpackDepthCode(texture2D(u_gbuffer, uv).ba);
    codes[i] = code;
    // Strictly nearer wins; of equal depths the earlier sample, or the centre.
    if (code < nearestCode - 0.5 || (i == 4 && code < nearestCode + 0.5)) {
      nearestCode = code;
      nearestOffset = offset;
    }
  }
  vec3 result = center;
  if (u_feedback > 0.0) {
    // Reprojection through the velocity of the nearest surface (Karis 2014, slide 29): an edge of a moving object
    // keeps its history on both sides of the silhouette.
    vec2 nearestUv = v_uv + nearestOffset * u_texel;
    vec2 previousUv = v_uv - unpackVelocity(texture2D(u_velocity, nearestUv));
    bool keep = previousUv.x >= 0.0 && previousUv.y >= 0.0 && previousUv.x <= 1.0 && previousUv.y <= 1.0;
    // Disocclusion: what the previous frame saw there must be a surface this neighbourhood sees now, at the depth it
    // had then: between the nearest and the farthest depth of the 3x3 (the previous frame's jitter put its sample
    // anywhere within a pixel, on either side of a silhouette), moved by the camera's motion of the nearest point, with
    // 2 % to spare (a moving object moves little in depth in a frame). Where the 3x3 holds the background, anything
    // beyond the nearest passes. A pixel farther than one from what covered it last frame fails.
    float previousCode = unpackDepthCode(texture2D(u_previousGbuffer, previousUv).ba);
    if (isBackgroundCode(nearestCode)) {
      keep = keep && isBackgroundCode(previousCode);
    } else {
      vec3 p = viewPositionOnRay(farPlaneRay(nearestUv), nearestCode * (1.0 / 65535.0));
      float nearest = -p.z;
      float expected = -(u_viewToPreviousView * vec4(p, 1.0)).z;
      float farthest = nearest;
      for (int i = 0; i < 9; i++) farthest = max(farthest, isBackgroundCode(codes[i]) ? 1e30 : viewDistance(codes[i]));
      float previous = isBackgroundCode(previousCode) ? 1e30 : viewDistance(previousCode);
      float shift = expected - nearest, margin = 0.02 * expected;
      keep = keep && previous >= expected - margin && previous <= farthest + shift + margin;
    }
    if (keep) {
      // The history at previousUv, Catmull-Rom filtered from 4x4 NEAREST texels, each decoded first (an encoded
      // texel cannot be filtered). Bilinear filtering, re-applied every frame a pixel moves, blurs the history a
      // little more each frame (a pan at a sixth of a pixel per frame was blurrier than no antialiasing); Catmull-Rom
      // keeps it sharp (Karis 2014, slide 31), its negative lobes bounded by the clipping below.
      vec2 texelPosition = previousUv * u_size - 0.5;
      vec2 base = floor(texelPosition);
      vec2 f = texelPosition - base;
      vec4 wx = vec4(f.x * (-0.5 + f.x * (1.0 - 0.5 * f.x)), 1.0 + f.x * f.x * (-2.5 + 1.5 * f.x),
                     f.x * (0.5 + f.x * (2.0 - 1.5 * f.x)), f.x * f.x * (-0.5 + 0.5 * f.x));
      vec4 wy = vec4(f.y * (-0.5 + f.y * (1.0 - 0.5 * f.y)), 1.0 + f.y * f.y * (-2.5 + 1.5 * f.y),
                     f.y * (0.5 + f.y * (2.0 - 1.5 * f.y)), f.y * f.y * (-0.5 + 0.5 * f.y));
      vec3 history = vec3(0.0);
      vec2 nearestTexel = floor(texelPosition + 0.5);
      if (all(lessThan(abs(texelPosition - nearestTexel), vec2(1.0 / 512.0)))) {
        // On a texel (a still view, the common case): its weights are (0, 1, 0, 0), one fetch.
        history = fetchWeighted(u_history, (nearestTexel + 0.5) * u_texel);
      } else {
        for (int j = 0; j < 4; j++) {
          float weightY = j == 0 ? wy.x : (j == 1 ? wy.y : (j == 2 ? wy.z : wy.w));
          for (int i = 0; i < 4; i++) {
            float weightX = i == 0 ? wx.x : (i == 1 ? wx.y : (i == 2 ? wx.z : wx.w));
            vec2 uv = (base + vec2(float(i) - 0.5, float(j) - 0.5)) * u_texel;
            history += weightX * weightY * fetchWeighted(u_history, uv);
          }
        }
      }
      vec3 mean = sum * (1.0 / 9.0);
      vec3 sigma = sqrt(max(sumSquares * (1.0 / 9.0) - mean * mean, 0.0));
      history = taaClipTowardsMean(history, mean, u_gamma * sigma);
      result = mix(center, history, u_feedback);
    }
  }
  gl_FragColor = encodeHdr(taaFromYCoCg(taaToneUnweight(result)));
}

#elif TAA_STAGE == 1
uniform sampler2D u_resolved;  // the history target stage 0 wrote
#if TAA_SHARPEN
uniform vec2 u_texel;
uniform float u_sharpen;

vec3 fetchWeighted(vec2 uv) { return taaToneWeight(taaToYCoCg(decodeHdr(texture2D(u_resolved, uv)))); }
#endif

void main() {
#if TAA_SHARPEN
  vec3 c = fetchWeighted(v_uv);
  vec3 around = fetchWeighted(v_uv + vec2(u_texel.x, 0.0)) + fetchWeighted(v_uv - vec2(u_texel.x, 0.0)) +
                fetchWeighted(v_uv + vec2(0.0, u_texel.y)) + fetchWeighted(v_uv - vec2(0.0, u_texel.y));
  vec3 sharpened = c + u_sharpen * (c - 0.25 * around);
  sharpened.x = clamp(sharpened.x, 0.0, 0.999);  // the tone-mapped luma stays below 1 (invertible)
  gl_FragColor = encodeHdr(max(taaFromYCoCg(taaToneUnweight(sharpened)), 0.0));
#else
  // The bytes as they are: each stored byte b reads back as b / 255 and is written back as b.
  gl_FragColor = texture2D(u_resolved, v_uv);
#endif
}

#else
uniform sampler2D u_gbuffer;

void main() { gl_FragColor = texture2D(u_gbuffer, v_uv); }
#endif
