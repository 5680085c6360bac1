// AO parameters: one table of names and ranges for the CLI, viewer and page; presets; spiral turns.
#include <cstdio>

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

TEST(AoSettings, EveryParameterRoundTripsThroughText) {
  AoSettings changed;
  changed.set("radius", "0.3");
  changed.set("bias", "0.0125");
  changed.set("samples", "13");
  changed.set("turns", "5");
  changed.set("falloff", "alchemy2011");
  changed.set("blur", "off");
  changed.set("blur-depth-sigma", "0.007");
  for (const AoSettings& original : {AoSettings{}, changed}) {
    AoSettings copy;
    for (const ParameterInfo& p : aoParameters()) {
      const std::string text = original.get(p.name);
      if (text.empty()) continue;  // "preset" when the values match no preset
      copy.set(p.name, text);
    }
    for (const ParameterInfo& p : aoParameters()) EXPECT_EQ(copy.get(p.name), original.get(p.name)) << p.name;
  }
  EXPECT_EQ(changed.get("radius"), "0.3");  // shortest exact text, not 0.300000012
  EXPECT_EQ(changed.get("blur"), "off");
  EXPECT_THROW(changed.get("colour"), InputError);
}

TEST(AoSettings, ParameterMetadataDescribesTheAcceptedValues) {
  for (const ParameterInfo& p : aoParameters()) {
    AoSettings settings;
    switch (p.kind) {
      case ParameterKind::Number:
      case ParameterKind::Integer: {
        ASSERT_LT(p.min, p.max) << p.name;
        char bounds[64];
        std::snprintf(bounds, sizeof bounds, "%g .. %g", p.min, p.max);
        EXPECT_EQ(p.range.rfind(bounds, 0), 0u) << p.name << ": " << p.range;
        if (std::string(p.name) == "turns") continue;  // also needs to be coprime with samples
        char text[32];
        std::snprintf(text, sizeof text, "%g", p.max);
        EXPECT_NO_THROW(settings.set(p.name, text)) << p.name;
        std::snprintf(text, sizeof text, "%g", p.max + 1.0);
        EXPECT_THROW(settings.set(p.name, text), InputError) << p.name;
        break;
      }
      case ParameterKind::Switch:
      case ParameterKind::Choice:
        ASSERT_FALSE(p.choices.empty()) << p.name;
        for (const std::string& choice : p.choices) {
          EXPECT_NO_THROW(settings.set(p.name, choice)) << p.name << "=" << choice;
          EXPECT_EQ(settings.get(p.name), choice) << p.name;
        }
        EXPECT_THROW(settings.set(p.name, "no-such-choice"), InputError) << p.name;
        break;
    }
  }
}

TEST(AoSettings, PresetReadsBackOnlyWhileTheValuesMatchIt) {
  AoSettings settings;
  EXPECT_EQ(settings.get("preset"), "medium");  // the defaults are the medium preset
  settings.set("preset", "ultra");
  EXPECT_EQ(settings.get("preset"), "ultra");
  settings.set("samples", "13");
  EXPECT_EQ(settings.get("preset"), "");
}

TEST(AoSettings, ValidateNamesTheParameterOutOfRange) {
  AoSettings settings;
  settings.radius = 0.0f;
  try {
    settings.validate();
    ADD_FAILURE() << "radius 0 passed validate()";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("radius = 0 is outside 0.01 .. 100"), std::string::npos) << e.what();
  }
  settings = AoSettings{};
  settings.spiralTurns = 11;  // shares a factor with 11 samples
  EXPECT_THROW(settings.validate(), InputError);
}
