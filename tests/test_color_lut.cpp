// CPU tests of colour grading's 3D LUT (src/encoding/ColorLut.h): .cube files read as the Adobe specification has
// them (comments, title, domain, Resolve's input range, CRLF lines), every malformation refused with its line, the
// trilinear lookup against the function a LUT samples, and the strip's layout, wrapping and bytes.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "base/Error.h"
#include <glm/common.hpp>
#include <glm/gtx/component_wise.hpp>

#include "encoding/ColorLut.h"

using namespace obscura;

namespace {

// The message a refused .cube gives, or "" when it is read.
std::string refusal(const std::string& text) {
  try {
    parseCubeLut(text, "grade.cube");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string identityCube(int size) { return writeCubeLut(ColorLut::identity(size)); }

}  // namespace

TEST(ColorLut, ReadsTheCubeFormat) {
  const std::string text =
      "# made by hand\r\n"
      "TITLE \"warm\"\r\n"
      "\r\n"
      "LUT_3D_SIZE 2\r\n"
      "DOMAIN_MIN 0 0 0\r\n"
      "DOMAIN_MAX 1 1 1\r\n"
      "0 0 0\r\n1 0 0\r\n0 1 0\r\n1 1 0\r\n"
      "# a comment among the rows\r\n"
      "0 0 1\r\n1 0 1\r\n0 1 1\r\n1e0 1.0 1\r\n";
  const ColorLut lut = parseCubeLut(text, "warm.cube");
  EXPECT_EQ(lut.title, "warm");
  EXPECT_EQ(lut.size, 2);
  EXPECT_EQ(lut.at(1, 0, 0), glm::vec3(1.0f, 0.0f, 0.0f)) << "red changes fastest";
  EXPECT_EQ(lut.at(0, 1, 0), glm::vec3(0.0f, 1.0f, 0.0f));
  EXPECT_EQ(lut.at(0, 0, 1), glm::vec3(0.0f, 0.0f, 1.0f));
  EXPECT_EQ(lut.at(1, 1, 1), glm::vec3(1.0f));
  // Resolve's input range, and a written LUT read back.
  const ColorLut ranged = parseCubeLut("LUT_3D_INPUT_RANGE -0.5 2\nLUT_3D_SIZE 2\n" +
                                           identityCube(2).substr(identityCube(2).find('\n') + 1),
                                       "ranged.cube");
  EXPECT_EQ(ranged.domainMin, glm::vec3(-0.5f));
  EXPECT_EQ(ranged.domainMax, glm::vec3(2.0f));
  const ColorLut again = parseCubeLut(writeCubeLut(ColorLut::identity(17)), "again.cube");
  EXPECT_EQ(again.values, ColorLut::identity(17).values);
}

TEST(ColorLut, AMalformedCubeIsRefusedWithItsLine) {
  const std::string rows = identityCube(2).substr(identityCube(2).find('\n') + 1);
  struct Case {
    std::string text, expected;
  };
  const Case cases[] = {
      {"LUT_3D_SIZE 2\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n", "line 8: the file ends after 7 rows"},
      {"LUT_3D_SIZE 2\n" + rows + "1 1 1\n", "line 10: more rows than LUT_3D_SIZE 2 makes (8)"},
      {"LUT_3D_SIZE 2\n0 0 0\n1 0 x\n", "line 3: 'x' is not a number"},
      {"LUT_3D_SIZE 2\n0 0\n", "line 2: expected three numbers, got '0 0'"},
      {"0 0 0\nLUT_3D_SIZE 2\n", "line 1: a row of the table before LUT_3D_SIZE"},
      {"LUT_3D_SIZE 1\n", "line 1: LUT_3D_SIZE must be a whole number from 2 to 256"},
      {"LUT_3D_SIZE 2.5\n", "line 1: LUT_3D_SIZE must be"},
      {"LUT_3D_SIZE 300\n", "line 1: LUT_3D_SIZE must be"},
      {"LUT_1D_SIZE 1024\n", "line 1: a 1D LUT"},
      {"# nothing\nLUT_3D_SIZE 2\nGAMMA 2.2\n", "line 3: unknown keyword 'GAMMA'"},
      {"LUT_3D_SIZE 2\n" + rows + "DOMAIN_MIN 0 0 0\n", "line 10: 'DOMAIN_MIN' after the table's rows"},
      {"DOMAIN_MIN 0 0 1\nDOMAIN_MAX 1 1 1\n", "line 2: the domain's minimum must lie below its maximum"},
      {"DOMAIN_MIN 0 0 2\nLUT_3D_SIZE 2\n" + rows, "line 1: the domain's minimum must lie below its maximum"},
      {"DOMAIN_MIN 0 0\n", "line 1: expected three numbers after DOMAIN_MIN"},
      {"LUT_3D_SIZE 2\nLUT_3D_SIZE 2\n", "line 2: a second LUT_3D_SIZE"},
      {"TITLE no quotes\n", "line 1: TITLE needs its text in double quotes"},
      {"LUT_3D_SIZE 2\n0 0 inf\n", "line 2: 'inf' is not a number"},
      {"# only a comment\n", "grade.cube: no LUT_3D_SIZE"},
      {"", "grade.cube: no LUT_3D_SIZE"},
  };
  for (const Case& c : cases) {
    const std::string why = refusal(c.text);
    EXPECT_NE(why.find(c.expected), std::string::npos) << "got: '" << why << "' for:\n" << c.text;
    EXPECT_EQ(why.rfind("grade.cube", 0), 0u) << why;
    EXPECT_EQ(why.find('\n'), std::string::npos) << "one line: " << why;
  }
  EXPECT_EQ(refusal(identityCube(2)), "");
  EXPECT_THROW(readCubeLut("/no/such/file.cube"), InputError);
}

TEST(ColorLut, TrilinearLookupFollowsTheFunctionItSamples) {
  // The identity is exact at any size (without the bytes), and within half a byte as stored.
  const ColorLut identity = ColorLut::identity(33);
  float worstExact = 0.0f, worstStored = 0.0f;
  for (float r = 0.0f; r <= 1.0f; r += 0.0371f)
    for (float g = 0.0f; g <= 1.0f; g += 0.0419f)
      for (float b = 0.0f; b <= 1.0f; b += 0.0533f) {
        const glm::vec3 c(r, g, b);
        worstExact = std::max(worstExact, glm::compMax(glm::abs(identity.apply(c, false) - c)));
        worstStored = std::max(worstStored, glm::compMax(glm::abs(identity.apply(c) - c)));
      }
  EXPECT_LT(worstExact, 1e-5f);
  EXPECT_LE(worstStored, 0.5f / 255.0f + 1e-6f);
  // A smooth function: a warm grade with a gentle S-curve and some crosstalk between channels.
  auto grade = [](const glm::vec3& c) {
    const glm::vec3 s = c * c * (3.0f - 2.0f * c);
    return glm::clamp(glm::vec3(0.8f * s.r + 0.2f * c.g, 0.9f * s.g + 0.05f * c.b, 0.85f * s.b + 0.1f * c.r), 0.0f,
                      1.0f);
  };
  const ColorLut lut = ColorLut::of(33, grade);
  float worst = 0.0f;
  for (float r = 0.0f; r <= 1.0f; r += 0.0371f)
    for (float g = 0.0f; g <= 1.0f; g += 0.0419f)
      for (float b = 0.0f; b <= 1.0f; b += 0.0533f) {
        const glm::vec3 c(r, g, b);
        worst = std::max(worst, glm::compMax(glm::abs(lut.apply(c) - grade(c))));
      }
  EXPECT_LT(worst, 1.5f / 255.0f);
  // Outside the domain the input clamps.
  EXPECT_EQ(identity.apply(glm::vec3(-1.0f, 2.0f, 0.5f), false), glm::vec3(0.0f, 1.0f, 0.5f));
}

TEST(ColorLut, TheStripLaysSlicesSideBySideAndWraps) {
  const ColorLut lut = ColorLut::identity(4);
  const LutStrip strip = lutStrip(lut, 4096);
  EXPECT_EQ(strip.width, 16);
  EXPECT_EQ(strip.height, 4);
  // Texel (r + 4 b, g) holds (r, g, b) / 3 as bytes.
  auto texel = [&](const LutStrip& s, int x, int y) { return &s.rgba[(static_cast<size_t>(y) * s.width + x) * 4]; };
  EXPECT_EQ(texel(strip, 1 + 4 * 2, 3)[0], 85);
  EXPECT_EQ(texel(strip, 1 + 4 * 2, 3)[1], 255);
  EXPECT_EQ(texel(strip, 1 + 4 * 2, 3)[2], 170);
  EXPECT_EQ(texel(strip, 1 + 4 * 2, 3)[3], 255);
  // In textures 8 texels wide, two slices a row, two rows of slices.
  const LutStrip wrapped = lutStrip(lut, 8);
  EXPECT_EQ(wrapped.slicesPerRow, 2);
  EXPECT_EQ(wrapped.width, 8);
  EXPECT_EQ(wrapped.height, 8);
  EXPECT_EQ(texel(wrapped, 1 + 4 * 0, 3 + 4 * 1)[2], 170);  // slice 2: first of the second row
  EXPECT_THROW(lutStrip(ColorLut::identity(65), 64), InputError);
  EXPECT_EQ(lutStrip(ColorLut::identity(65), 4096).slicesPerRow, 63);
}
