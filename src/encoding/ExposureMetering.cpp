#include "encoding/ExposureMetering.h"

#include <algorithm>
#include <cmath>

#include "encoding/LinearDepthPacking.h"

namespace obscura::ExposureMetering {
namespace {

constexpr float kRange = kMaxLog2 - kMinLog2;

std::uint16_t unitCode(float unit) {
  return static_cast<std::uint16_t>(std::floor(std::clamp(unit, 0.0f, 1.0f) * 65535.0f + 0.5f));
}

}  // namespace

float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

bool metered(const glm::vec3& linear) { return luminance(linear) >= kBlack; }

float meteredLog2(const glm::vec3& linear) {
  return std::clamp(std::log2(std::max(luminance(linear), kBlack)), kMinLog2, kMaxLog2);
}

std::uint16_t codeFromLog2(float x) { return unitCode((x - kMinLog2) / kRange); }
float log2FromCode(std::uint16_t code) { return kMinLog2 + static_cast<float>(code) * (kRange / 65535.0f); }
std::uint16_t codeFromWeight(float w) { return unitCode(w); }
float weightFromCode(std::uint16_t code) { return static_cast<float>(code) / 65535.0f; }

std::array<std::uint8_t, 4> bytesFromBlock(const MeteredBlock& block) {
  const auto mean = LinearDepthPacking::bytesFromCode(codeFromLog2(block.meanLog2));
  const auto weight = LinearDepthPacking::bytesFromCode(codeFromWeight(block.weight));
  return {mean[0], mean[1], weight[0], weight[1]};
}

MeteredBlock blockFromBytes(const std::uint8_t* bytes) {
  return {log2FromCode(LinearDepthPacking::codeFromBytes(bytes[0], bytes[1])),
          weightFromCode(LinearDepthPacking::codeFromBytes(bytes[2], bytes[3]))};
}

float meteringWeight(Metering metering, glm::vec2 uv, float aspect) {
  if (metering != Metering::Centre) return 1.0f;
  // uv - 0.5 in units of half the height: x scaled by the aspect (width / height).
  const glm::vec2 d((uv.x - 0.5f) * 2.0f * aspect, (uv.y - 0.5f) * 2.0f);
  return std::exp(-2.0f * (d.x * d.x + d.y * d.y));
}

glm::ivec2 meterGridSize(glm::ivec2 frame) { return (frame + glm::ivec2(kMeterBlock - 1)) / kMeterBlock; }

int reductionCount(glm::ivec2 frame) {
  glm::ivec2 level = meterGridSize(frame);
  int count = 0;
  while (level.x > kReduceBlock || level.y > kReduceBlock) {
    level = (level + glm::ivec2(kReduceBlock - 1)) / kReduceBlock;
    ++count;
  }
  return count;
}

int histogramBin(float log2Value) {
  const float unit = (std::clamp(log2Value, kMinLog2, kMaxLog2) - kMinLog2) / kRange;
  return std::min(static_cast<int>(std::floor(unit * kHistogramBins)), kHistogramBins - 1);
}

float histogramBinCentre(int bin) { return kMinLog2 + (static_cast<float>(bin) + 0.5f) * (kRange / kHistogramBins); }

float percentileMean(const std::vector<std::uint32_t>& counts, float low, float high) {
  double total = 0.0;
  for (std::uint32_t c : counts) total += c;
  if (total <= 0.0) return 0.0f;
  const double from = total * low, to = total * high;
  double below = 0.0, sum = 0.0, weight = 0.0;
  for (size_t bin = 0; bin < counts.size(); ++bin) {
    const double start = below, end = below + counts[bin];
    const double inside = std::max(0.0, std::min(end, to) - std::max(start, from));
    sum += inside * histogramBinCentre(static_cast<int>(bin));
    weight += inside;
    below = end;
  }
  return weight > 0.0 ? static_cast<float>(sum / weight) : 0.0f;
}

float adapt(float adaptedLog2, float targetLog2, float seconds, float up, float down) {
  const float speed = targetLog2 > adaptedLog2 ? up : down;
  return adaptedLog2 + (targetLog2 - adaptedLog2) * (1.0f - std::exp(-speed * std::max(seconds, 0.0f)));
}

float exposureEv(float adaptedLog2, float compensation, float minEv, float maxEv) {
  return std::clamp(std::clamp(kKeyLog2 - adaptedLog2, minEv, maxEv) + compensation, kMinLog2, kMaxLog2);
}

}  // namespace obscura::ExposureMetering
