// Auto exposure's histogram (percentile metering), scattered: one point per sample of the meter grid, placed in its
// log2 luminance's bin and drawn with additive blending (GL_ONE, GL_ONE) into a 128 x 64 RGBA8 target cleared to 0.
// Sample i adds one count to one channel of one row, (i mod 256) choosing which, so no byte takes more than
// ceil(samples / 256) counts: at most ExposureMetering::kHistogramMaxSamples = 65280 samples never saturate a byte
// (255). Needs a vertex texture unit (texture2DLod in the vertex stage); without one the effect meters the average.
#include "lib/packing.glsl"
#include "lib/exposure.glsl"

attribute float a_position;  // the sample's index i, 0 .. samples - 1

uniform sampler2D u_meter;   // the meter grid (auto_exposure.frag, stage 0)
uniform vec2 u_meterSize;    // its size in texels
uniform float u_stride;      // grid texels per sample, >= 1: a grid larger than the samples is sampled evenly

varying vec4 v_count;

void main() {
  float texel = floor(a_position * u_stride);
  // + 0.5 before each floor: a division by an integer that lands on an integer stays on it.
  float row = floor((texel + 0.5) / u_meterSize.x);
  float column = texel - row * u_meterSize.x;
  vec4 block = texture2DLod(u_meter, (vec2(column, row) + 0.5) / u_meterSize, 0.0);
  float l = unpackLog2(block.rg);
  float bin = min(floor((l - EXPOSURE_MIN_LOG2) * (128.0 / EXPOSURE_RANGE)), 127.0);
  float slot = a_position - 256.0 * floor((a_position + 0.5) * (1.0 / 256.0));
  float histogramRow = floor((slot + 0.5) * 0.25);
  float channel = slot - 4.0 * histogramRow;
  // One count, written as (1 + 0.25) / 255: stored as one more whether the target rounds or truncates.
  v_count = vec4(equal(vec4(channel), vec4(0.0, 1.0, 2.0, 3.0))) * (1.25 / 255.0);
  // A block with nothing lit in it (weight 0) is not a sample: its point lies outside the clip volume.
  float outside = unpackWeight(block.ba) > 0.0 ? 0.0 : 4.0;
  gl_Position = vec4((bin + 0.5) * (2.0 / 128.0) - 1.0 + outside, (histogramRow + 0.5) * (2.0 / 64.0) - 1.0, 0.0,
                     1.0);
  gl_PointSize = 1.0;
}
