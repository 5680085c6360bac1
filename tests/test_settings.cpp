// AO parameters: one table of names and ranges for the CLI, viewer and page; presets; spiral turns.
#include <gtest/gtest.h>

#include "core/AoSettings.h"
#include "core/Error.h"
#include "core/SaoKernel.h"

using namespace obscura;

TEST(AoSettings, DefaultsAreValidAndUseTheBestSpiral) {
  const AoSettings settings;
  EXPECT_NO_THROW(settings.validate());
  EXPECT_EQ(settings.spiralTurns, SaoKernel::bestSpiralTurns(settings.samples));
}

TEST(AoSettings, PresetTurnsAreCoprimeBestTurns) {
  for (const PresetInfo& preset : qualityPresets()) {
    EXPECT_EQ(preset.spiralTurns, SaoKernel::bestSpiralTurns(preset.samples)) << preset.name;
    AoSettings settings;
    settings.set("preset", preset.name);
    EXPECT_EQ(settings.samples, preset.samples);
    EXPECT_NO_THROW(settings.validate());
  }
}

TEST(AoSettings, SpiralTurnsMatchTheReferenceTable) {
  // Values of the SAO reference code's tuned table (G3D) that our lattice criterion reproduces.
  EXPECT_EQ(SaoKernel::bestSpiralTurns(8), 3);
  EXPECT_EQ(SaoKernel::bestSpiralTurns(11), 3);
  EXPECT_EQ(SaoKernel::bestSpiralTurns(13), 5);
  EXPECT_EQ(SaoKernel::bestSpiralTurns(21), 8);
  EXPECT_EQ(SaoKernel::bestSpiralTurns(32), 7);
  for (int s = 1; s <= 64; ++s) EXPECT_EQ(SaoKernel::greatestCommonDivisor(SaoKernel::bestSpiralTurns(s), s), 1) << s;
}

TEST(AoSettings, SetRefusesUnknownNamesAndOutOfRangeValues) {
  AoSettings settings;
  const std::pair<std::pair<const char*, const char*>, const char*> cases[] = {
      {{"radius", "0"}, "radius: 0 is out of range"},
      {{"radius", "abc"}, "radius: expected a number"},
      {{"radius", "nan"}, "radius: expected a number"},
      {{"samples", "2.5"}, "samples: expected a whole number"},
      {{"samples", "1000"}, "samples: 1000 is out of range"},
      {{"turns", "4"}, "shares a factor"},  // with the default 11 samples: fine; after samples=8, 4 is not coprime
      {{"blur", "maybe"}, "blur: expected on or off"},
      {{"falloff", "cubic"}, "falloff: expected sao2012 or alchemy2011"},
      {{"preset", "extreme"}, "preset: expected low, medium, high or ultra"},
      {{"colour", "red"}, "unknown parameter 'colour'"},
  };
  settings.set("samples", "8");
  for (const auto& [input, expect] : cases) {
    try {
      settings.set(input.first, input.second);
      ADD_FAILURE() << input.first << "=" << input.second << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(settings.validate());  // failed sets left the settings valid
}

TEST(AoSettings, EveryDocumentedParameterIsAccepted) {
  for (const ParameterInfo& p : aoParameters()) {
    EXPECT_NE(std::string(p.help), "") << p.name;
    EXPECT_NE(std::string(p.range), "") << p.name;
  }
  AoSettings settings;
  settings.set("radius", "2.5");
  settings.set("falloff", "alchemy2011");
  settings.set("blur-radius", "0");
  EXPECT_FLOAT_EQ(settings.radius, 2.5f);
  EXPECT_EQ(settings.falloff, Falloff::Alchemy2011);
  EXPECT_EQ(settings.blurRadius, 0);
}
