// Tests of the built-in presets: datasheet numbers mapped as presets.h says,
// and each preset's class consistent with Table 1 from its own numbers.
#include "foglab/sim/presets.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "foglab/core/error.h"
#include "foglab/sim/lab2_variants.h"
#include "support/expect.h"

namespace foglab::sim {
namespace {

using ::testing::HasSubstr;
using test::message_of;

TEST(Presets, EveryClassAgreesWithTable1FromThePresetsOwnNumbers) {
  for (const Preset& p : presets()) {
    // the ADEV floor of the flicker term, the preset's bias instability
    const double bi = std::sqrt(2.0 * std::log(2.0) / M_PI) * p.model.noise.B;
    const double arw = p.model.noise.N / 60.0;
    // (1 + 1e-12): a datasheet value on a class boundary (0.01 deg/h) must
    // not drop below it by rounding in BI -> B -> BI
    EXPECT_EQ(p.accuracy_class, to_string(classify(bi * (1 + 1e-12), arw).accuracy_class))
        << p.name;
    // the model's ADEV minimum over a long range approaches the same floor
    const AdevMinimum m = adev_minimum(p.model.noise, 0.01, 1e7);
    EXPECT_NEAR(m.adev_deg_h, bi, 0.01 * bi) << p.name;
  }
}

TEST(Presets, KvhDatasheetFiguresMapToNAndB) {
  struct Row {
    const char* name;
    double arw, bi;
    const char* cls;
  };
  for (const Row& r : {Row{"kvh-dsp-3000", 0.067, 1.0, "tactical"},
                       Row{"kvh-dsp-1750", 0.013, 0.1, "intermediate"},
                       Row{"kvh-dsp-1760", 0.012, 0.05, "intermediate"}}) {
    const Preset& p = find_preset(r.name);
    EXPECT_DOUBLE_EQ(p.model.noise.N, 60.0 * r.arw) << r.name;
    EXPECT_NEAR(p.model.noise.B, r.bi / 0.664, 1e-3 * r.bi) << r.name;
    EXPECT_EQ(p.accuracy_class, r.cls) << r.name;
  }
}

TEST(Presets, Table3NoiseDensityIsNItself) {
  EXPECT_DOUBLE_EQ(find_preset("fog-600s").model.noise.N, 0.7);
  EXPECT_DOUBLE_EQ(find_preset("oius-2000").model.noise.N, 0.03);
  EXPECT_DOUBLE_EQ(find_preset("oius-1000").model.noise.N, 0.07);
  EXPECT_DOUBLE_EQ(find_preset("vog-120").model.noise.N, 0.18);
  EXPECT_DOUBLE_EQ(find_preset("fog-120").model.noise.N, 0.072);
  EXPECT_DOUBLE_EQ(find_preset("fog-1000").model.noise.N, 0.04);
  EXPECT_DOUBLE_EQ(find_preset("elektropribor-fog").model.noise.N, 0.04);
  EXPECT_EQ(find_preset("oius-2000").accuracy_class, "navigation");
  EXPECT_EQ(find_preset("fog-600s").accuracy_class, "intermediate");  // ARW 0.0117 decides
}

TEST(Presets, OneArchetypePerClassInsideItsOwnClass) {
  for (const char* cls : {"strategic", "navigation", "intermediate", "tactical", "consumer"}) {
    const Preset& p = find_preset(std::string("class-") + cls);
    EXPECT_EQ(p.accuracy_class, cls);
    const ClassVerdict v = classify(0.6643 * p.model.noise.B, p.model.noise.N / 60.0);
    EXPECT_EQ(to_string(v.by_bias_instability), cls);
    EXPECT_EQ(to_string(v.by_arw), cls);
  }
}

TEST(Presets, NamesAreUniqueLowercaseHyphenatedAndDescribed) {
  std::set<std::string> names;
  for (const Preset& p : presets()) {
    EXPECT_TRUE(names.insert(p.name).second) << p.name;
    for (const char c : p.name) {
      EXPECT_TRUE((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-') << p.name;
    }
    EXPECT_THAT(p.description, HasSubstr("B = BI/0.664")) << p.name;
    EXPECT_GT(p.sample_rate_hz, 0.0);
  }
  EXPECT_EQ(presets().size(), 15u);
}

TEST(Presets, UnknownNameListsTheNames) {
  const std::string message = message_of<UsageError>([] { find_preset("kvh-dsp-9999"); });
  EXPECT_THAT(message, HasSubstr("unknown preset 'kvh-dsp-9999'"));
  EXPECT_THAT(message, HasSubstr("kvh-dsp-3000"));
  EXPECT_THAT(message, HasSubstr("class-navigation"));
  EXPECT_THAT(message, HasSubstr("elektropribor-fog"));
}

TEST(AccuracyClass, Table1BoundariesGoToTheBetterClass) {
  EXPECT_EQ(class_by_bias_instability(1.0), AccuracyClass::intermediate);
  EXPECT_EQ(class_by_bias_instability(1.01), AccuracyClass::tactical);
  EXPECT_EQ(class_by_bias_instability(0.0099), AccuracyClass::navigation);
  EXPECT_EQ(class_by_bias_instability(0.0009), AccuracyClass::strategic);
  EXPECT_EQ(class_by_bias_instability(11.0), AccuracyClass::consumer);
  EXPECT_EQ(class_by_arw(0.5), AccuracyClass::tactical);
  EXPECT_EQ(class_by_arw(0.6), AccuracyClass::consumer);
  EXPECT_EQ(class_by_arw(0.004), AccuracyClass::navigation);
  EXPECT_EQ(class_by_arw(0.0002), AccuracyClass::strategic);
  const ClassVerdict v = classify(1.0, 0.067);
  EXPECT_EQ(v.accuracy_class, AccuracyClass::tactical);
  EXPECT_EQ(v.decided_by, ClassCriterion::arw);
}

}  // namespace
}  // namespace foglab::sim
