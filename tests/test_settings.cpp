// Parameters: the AO's own (names, ranges, presets, spiral turns), and the frame's (every effect's under its prefix,
// aliases, the frame preset): one table for the CLI, the viewers and the page.
#include <cstdio>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "base/Error.h"
#include "effects/ao/AoSettings.h"
#include "effects/ao/SaoKernel.h"
#include "effects/fxaa/FxaaEffect.h"
#include "effects/tonemap/TonemapEffect.h"
#include "renderer/RenderSettings.h"

using namespace obscura;

namespace {

// Each case, {{name, value}, message}: set(name, value) throws InputError whose message contains `message`.
using RefusalCase = std::pair<std::pair<const char*, const char*>, const char*>;
template <class Settings, size_t N>
void expectRefusals(Settings& settings, const RefusalCase (&cases)[N]) {
  for (const auto& [input, expect] : cases) {
    try {
      settings.set(input.first, input.second);
      ADD_FAILURE() << input.first << "=" << input.second << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
    }
  }
}

}  // namespace

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
  const RefusalCase cases[] = {
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
  expectRefusals(settings, cases);
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

TEST(AoSettings, DefaultsAreTheMediumPreset) {
  // The tuned estimator parameters are looked up for `preset`, so the default fields must be that preset's.
  const AoSettings defaults;
  AoSettings medium;
  medium.applyPreset(QualityPreset::Medium);
  EXPECT_EQ(defaults.preset, QualityPreset::Medium);
  EXPECT_EQ(defaults.samples, medium.samples);
  EXPECT_EQ(defaults.spiralTurns, medium.spiralTurns);
  EXPECT_EQ(defaults.blurRadius, medium.blurRadius);
  EXPECT_EQ(defaults.blurStride, medium.blurStride);
  EXPECT_EQ(defaults.halfResolution, medium.halfResolution);
}

TEST(AoSettings, EstimatorParametersAreTunedUnlessSetExplicitly) {
  AoSettings settings;
  settings.set("preset", "high");
  EXPECT_EQ(settings.preset, QualityPreset::High);
  settings.set("radius", "2");
  const EstimatorKnots tuned = tunedEstimatorKnots(settings.estimator, QualityPreset::High);
  for (int j = 0; j < kEstimatorKnots; ++j) {
    EXPECT_FLOAT_EQ(settings.estimatorKnots().at[j].intensity, tuned.at[j].intensity);
    EXPECT_FLOAT_EQ(settings.estimatorKnots().at[j].bias, tuned.at[j].bias);
    EXPECT_FLOAT_EQ(settings.estimatorKnots().at[j].contrast, tuned.at[j].contrast);
    EXPECT_FLOAT_EQ(settings.estimatorKnots().at[j].thickness, tuned.at[j].thickness);
  }
  // Keyed by the radius in pixels and the preset, not by the radius: another radius in scene units, the same knots.
  settings.set("radius", "200");
  EXPECT_FLOAT_EQ(settings.estimatorKnots().at[2].intensity, tuned.at[2].intensity);

  settings.set("intensity", "2.5");
  settings.set("bias", "0.03");
  settings.set("contrast", "1.5");
  settings.set("thickness", "2");
  for (float pixels : {1.0f, 4.0f, 23.0f, 500.0f}) {  // an explicit value holds at every radius in pixels
    EXPECT_FLOAT_EQ(settings.estimatorAt(pixels).intensity, 2.5f);
    EXPECT_FLOAT_EQ(settings.estimatorAt(pixels).bias, 0.03f);
    EXPECT_FLOAT_EQ(settings.estimatorAt(pixels).contrast, 1.5f);
    EXPECT_FLOAT_EQ(settings.estimatorAt(pixels).thickness, 2.0f);
  }
  settings.set("thickness", "auto");
  EXPECT_FLOAT_EQ(settings.estimatorAt().thickness, tuned.interpolate(kShownKnotPixels).thickness);
  EXPECT_EQ(settings.get("thickness"), "auto");

  settings.set("intensity", "auto");
  EXPECT_FLOAT_EQ(settings.estimatorAt().intensity, tuned.interpolate(kShownKnotPixels).intensity);
  EXPECT_FLOAT_EQ(settings.estimatorAt().bias, 0.03f);
}

TEST(AoSettings, EffectiveValuesResolveAuto) {
  AoSettings settings;
  settings.set("radius", "2");
  EXPECT_EQ(settings.get("intensity"), "auto");
  EXPECT_FLOAT_EQ(std::stof(settings.effective("intensity")), settings.estimatorAt().intensity);
  settings.set("intensity", "1.25");
  EXPECT_EQ(settings.effective("intensity"), "1.25");
  EXPECT_EQ(settings.effective("radius"), settings.get("radius"));
}

TEST(AoSettings, TunedKnotsInterpolateInLogRadiusAndHoldAtTheEnds) {
  for (const PresetInfo& preset : qualityPresets()) {
    AoSettings settings;
    settings.applyPreset(preset.preset);
    EXPECT_NO_THROW(settings.validate()) << preset.name;
    const EstimatorKnots knots = tunedEstimatorKnots(settings.estimator, preset.preset);
    for (int j = 0; j < kEstimatorKnots; ++j) {
      // At a knot, its own values; halfway (in log2) between two knots, their mean.
      EXPECT_FLOAT_EQ(knots.interpolate(estimatorKnotPixels(j)).intensity, knots.at[j].intensity);
      if (j + 1 < kEstimatorKnots) {
        EXPECT_NEAR(knots.interpolate(estimatorKnotPixels(j) * std::sqrt(2.0f)).bias,
                    0.5f * (knots.at[j].bias + knots.at[j + 1].bias), 1e-5f);
        EXPECT_NEAR(knots.interpolate(estimatorKnotPixels(j) * std::sqrt(2.0f)).thickness,
                    0.5f * (knots.at[j].thickness + knots.at[j + 1].thickness), 1e-5f);
      }
    }
    EXPECT_FLOAT_EQ(knots.interpolate(0.5f).contrast, knots.at[0].contrast);
    EXPECT_FLOAT_EQ(knots.interpolate(4096.0f).contrast, knots.at[kEstimatorKnots - 1].contrast);
    // Every knot comes from the fitted table (none left at the paper's values).
    for (const EstimatorParameters& e : knots.at)
      EXPECT_FALSE(e.intensity == kPaperEstimatorParameters.intensity && e.bias == kPaperEstimatorParameters.bias &&
                   e.contrast == kPaperEstimatorParameters.contrast)
          << preset.name;
  }
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

namespace {

// A number's largest value is accepted and a value past it refused (settings: AoSettings by local names, or
// RenderSettings by full ones).
template <typename Settings>
void expectTheLargestValueAndNoMore(Settings& settings, const ParameterInfo& p) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", p.max);
  EXPECT_NO_THROW(settings.set(p.name, text)) << p.name;
  std::snprintf(text, sizeof text, "%g", p.max + std::max(1.0, 0.01 * p.max));
  EXPECT_THROW(settings.set(p.name, text), InputError) << p.name;
}

// Every choice is accepted (and reads back, unless `readsBack` is false: a preset reads as what the values match) and
// an unknown one refused.
template <typename Settings>
void expectEveryChoiceAndNoOther(Settings& settings, const ParameterInfo& p, bool readsBack = true) {
  ASSERT_FALSE(p.choices.empty()) << p.name;
  for (const std::string& choice : p.choices) {
    EXPECT_NO_THROW(settings.set(p.name, choice)) << p.name << "=" << choice;
    if (readsBack) {
      EXPECT_EQ(settings.get(p.name), choice) << p.name;
    }
  }
  EXPECT_THROW(settings.set(p.name, "no-such-choice"), InputError) << p.name;
}

}  // namespace

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
        expectTheLargestValueAndNoMore(settings, p);
        break;
      }
      case ParameterKind::Switch:
      case ParameterKind::Choice:
        expectEveryChoiceAndNoOther(settings, p);
        break;
      case ParameterKind::Color:
      case ParameterKind::Text:
        ADD_FAILURE() << p.name << ": the AO has no colour or text parameter";
        break;
    }
  }
}

TEST(AoSettings, ExplicitEstimatorParametersKeepTheirRanges) {
  AoSettings settings;
  const RefusalCase cases[] = {
      {{"intensity", "25"}, "intensity: 25 is out of range (0 .. 20)"},
      {{"bias", "-0.1"}, "bias: -0.1 is out of range (0 .. 1 fraction of radius)"},
      {{"contrast", "0"}, "contrast: 0 is out of range (0.1 .. 10)"},
      {{"contrast", "automatic"}, "contrast: expected a number"},
  };
  expectRefusals(settings, cases);
  settings.intensity = 30.0f;  // set in code, out of range
  EXPECT_THROW(settings.validate(), InputError);
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
    EXPECT_NE(std::string(e.what()).find("radius = 0 is outside 0.0001 .. 1e+06"), std::string::npos) << e.what();
  }
  settings = AoSettings{};
  settings.spiralTurns = 11;  // shares a factor with 11 samples
  EXPECT_THROW(settings.validate(), InputError);
}

// --- The frame's settings: every effect's parameters under "effect.name", the switches, the aliases, the presets.

TEST(RenderSettings, NamesAreEffectDotParameterAndTheOldAoNamesAreAliases) {
  RenderSettings settings;
  settings.set("ao.radius", "2.5");
  EXPECT_EQ(settings.get("radius"), "2.5");
  settings.set("radius", "1.5");
  EXPECT_EQ(settings.get("ao.radius"), "1.5");
  EXPECT_FLOAT_EQ(settings.ao().radius, 1.5f);
  for (const char* effect : {"ao", "tonemap", "fxaa"}) {
    EXPECT_TRUE(settings.enabled(effect)) << effect;
    settings.set(effect, "off");
    EXPECT_FALSE(settings.enabled(effect)) << effect;
  }
  settings.set("tonemap.exposure", "1.5");
  settings.set("tonemap.operator", "agx");
  EXPECT_EQ(settings.get("tonemap.exposure"), "1.5");
  EXPECT_EQ(settings.of<TonemapSettings>().op, ToneMapOperator::AgX);
  EXPECT_EQ(RenderSettings::canonicalName("blur-radius"), "ao.blur-radius");
  EXPECT_EQ(RenderSettings::canonicalName("fxaa.subpix"), "fxaa.subpix");
  EXPECT_THROW(RenderSettings::canonicalName("exposure"), InputError) << "only the AO's old names are aliases";
  EXPECT_THROW(settings.set("tonemap.colour", "red"), InputError);
  // Every parameter belongs to an effect of the table, named after it; the aliases are the AO's old names.
  for (const ParameterInfo& p : RenderSettings::parameters()) {
    if (p.name == "preset") continue;
    EXPECT_TRUE(p.name == p.effect || p.name.rfind(p.effect + ".", 0) == 0) << p.name;
    if (!p.alias.empty()) {
      EXPECT_EQ("ao." + p.alias, p.name);
    }
  }
}

TEST(RenderSettings, MessagesNameTheParameterAsWritten) {
  RenderSettings settings;
  const RefusalCase cases[] = {
      {{"ao.radius", "0"}, "ao.radius: 0 is out of range"},
      {{"radius", "0"}, "radius: 0 is out of range"},
      {{"tonemap.exposure", "40"}, "tonemap.exposure: 40 is out of range (-16 .. 16 EV)"},
      {{"tonemap.operator", "filmic"}, "tonemap.operator: expected linear, reinhard, aces, neutral or agx"},
      {{"fxaa.quality", "16"}, "fxaa.quality: expected 10, 11, 12"},
      {{"fxaa", "maybe"}, "fxaa: expected on or off"},
      {{"preset", "extreme"}, "preset: expected low, medium, high or ultra"},
  };
  expectRefusals(settings, cases);
  EXPECT_NO_THROW(settings.validate());
}

TEST(RenderSettings, TheFramePresetSetsEveryEffectsPreset) {
  RenderSettings settings;
  EXPECT_EQ(settings.get("preset"), "medium");
  settings.set("preset", "high");
  EXPECT_EQ(settings.get("preset"), "high");
  EXPECT_EQ(settings.get("ao.preset"), "high");
  EXPECT_EQ(settings.get("fxaa.preset"), "high");
  EXPECT_EQ(settings.ao().samples, 16);
  EXPECT_EQ(settings.of<FxaaSettings>().quality, 29);
  settings.set("fxaa.preset", "low");  // one effect's own preset: the frame's no longer holds
  EXPECT_EQ(settings.get("preset"), "");
  EXPECT_EQ(settings.get("fxaa"), "on") << "fxaa.preset low alone keeps FXAA on";
  EXPECT_EQ(settings.get("fxaa.preset"), "low");
  EXPECT_EQ(settings.get("ao.preset"), "high");
  settings.set("ao.samples", "9");
  EXPECT_EQ(settings.get("ao.preset"), "");
  EXPECT_EQ(settings.ao().preset, QualityPreset::High) << "the AO remembers the preset it came from";
  // `preset low` turns FXAA off (FxaaEffect.cpp: on a weak device its pass costs about as much as the lit frame);
  // the other presets turn it on.
  settings.set("preset", "low");
  EXPECT_EQ(settings.get("fxaa"), "off");
  EXPECT_EQ(settings.get("preset"), "low");
  settings.set("preset", "medium");
  EXPECT_EQ(settings.get("fxaa"), "on");
}

TEST(RenderSettings, EveryParameterOfEveryEffectDescribesItsValuesAndRoundTrips) {
  for (const ParameterInfo& p : RenderSettings::parameters()) {
    EXPECT_NE(p.help, "") << p.name;
    EXPECT_NE(p.range, "") << p.name;
    RenderSettings settings;
    switch (p.kind) {
      case ParameterKind::Number:
      case ParameterKind::Integer: {
        ASSERT_LT(p.min, p.max) << p.name;
        if (p.name == "ao.turns") continue;  // also needs to be coprime with samples
        expectTheLargestValueAndNoMore(settings, p);
        break;
      }
      case ParameterKind::Switch:
      case ParameterKind::Choice:
        expectEveryChoiceAndNoOther(settings, p, p.name.find("preset") == std::string::npos);
        break;
      case ParameterKind::Color: {
        ASSERT_LT(p.min, p.max) << p.name;
        // Linear triples round-trip in their shortest form; a colour picker's sRGB hex decodes to linear.
        EXPECT_NO_THROW(settings.set(p.name, "0.25,0.5,1")) << p.name;
        EXPECT_EQ(settings.get(p.name), "0.25,0.5,1") << p.name;
        // (Where 0 is in range: an ASC CDL power is above 0.)
        if (p.min <= 0.0) {
          EXPECT_NO_THROW(settings.set(p.name, "#ff0000")) << p.name;
          EXPECT_EQ(settings.get(p.name), "1,0,0") << p.name;
        } else {
          EXPECT_THROW(settings.set(p.name, "#ff0000"), InputError) << p.name;
        }
        const std::string before = settings.get(p.name);
        for (const char* bad : {"1,2", "1,2,3,4", "#12345", "#gg0000", "a,b,c", ""})
          EXPECT_THROW(settings.set(p.name, bad), InputError) << p.name << "=" << bad;
        char text[64];
        std::snprintf(text, sizeof text, "0,0,%g", p.max + std::max(1.0, 0.01 * p.max));
        EXPECT_THROW(settings.set(p.name, text), InputError) << p.name;
        EXPECT_EQ(settings.get(p.name), before) << p.name << ": a refused value changes nothing";
        break;
      }
      case ParameterKind::Text: {
        // Built-in names round-trip. Any other text is a path: kept as it is where the effect opens it when it runs
        // (lighting.environment), or read at once where a bad file must be refused when it is set (lens-flare.dirt,
        // grading.lut), which leaves the value as it was.
        ASSERT_FALSE(p.choices.empty()) << p.name;
        for (const std::string& choice : p.choices) {
          EXPECT_NO_THROW(settings.set(p.name, choice)) << p.name << "=" << choice;
          EXPECT_EQ(settings.get(p.name), choice) << p.name;
        }
        std::string kept = settings.get(p.name);
        try {
          settings.set(p.name, "some/file.hdr");
          kept = "some/file.hdr";
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("some/file.hdr"), std::string::npos) << p.name << ": " << e.what();
        }
        EXPECT_EQ(settings.get(p.name), kept) << p.name;
        EXPECT_THROW(settings.set(p.name, ""), InputError) << p.name;
        EXPECT_EQ(settings.get(p.name), kept) << p.name << ": a refused value changes nothing";
        break;
      }
    }
    EXPECT_NO_THROW(settings.validate()) << p.name;
  }
}

TEST(RenderSettings, CopiesAreIndependent) {
  RenderSettings a;
  a.set("tonemap.exposure", "2");
  RenderSettings b = a;
  b.set("tonemap.exposure", "-1");
  a.set("ao.radius", "3");
  EXPECT_EQ(a.get("tonemap.exposure"), "2");
  EXPECT_EQ(b.get("tonemap.exposure"), "-1");
  EXPECT_EQ(b.get("ao.radius"), "1");
  const RenderSettings fromAo(a.ao());
  EXPECT_EQ(fromAo.get("ao.radius"), "3");
  EXPECT_EQ(fromAo.get("tonemap.exposure"), "0") << "the other effects at their defaults";
}

// The cached plan's key compares the shaping parameters by value each frame (ParameterBinding::same), and by their
// text only when they differ: for every parameter, `same` must agree with the text.
TEST(RenderSettings, EveryParameterComparesByValueAsItsTextDoes) {
  int compared = 0;
  const RenderSettings defaults;
  for (size_t row = 0; row < effectTable().size(); ++row) {
    for (const ParameterBinding& p : effectTable()[row].parameters) {
      const EffectSettingsBase& before = defaults.rowAt(row);
      EXPECT_TRUE(p.same(before, before)) << p.info.name;
      // Another value in range: the other switch position or choice, the far end of a number's range, a colour.
      std::vector<std::string> others;
      if (p.info.kind == ParameterKind::Switch || p.info.kind == ParameterKind::Choice ||
          p.info.kind == ParameterKind::Text)
        others = p.info.choices;
      if (p.info.kind == ParameterKind::Number || p.info.kind == ParameterKind::Integer)
        others = {formatShortest(static_cast<float>(p.info.min)), formatShortest(static_cast<float>(p.info.max))};
      if (p.info.kind == ParameterKind::Color) others = {"0.2,0.35,0.6"};
      for (const std::string& value : others) {
        std::unique_ptr<EffectSettingsBase> after = before.clone();
        try {
          p.set(*after, value);
        } catch (const InputError&) {
          continue;  // a value this parameter refuses with the others at their defaults
        }
        EXPECT_EQ(p.same(before, *after), p.get(before) == p.get(*after)) << p.info.name << " = " << value;
        if (p.get(before) != p.get(*after)) ++compared;
      }
    }
  }
  std::printf("%d changed values compared\n", compared);
  EXPECT_GT(compared, 100);
}
