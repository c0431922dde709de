// foglab — the accuracy classes of the lab manual's Table 1.
//
//   class         bias instability [deg/h]   angle random walk [deg/sqrt(h)]
//   strategic     < 0.001                    < 0.0003
//   navigation    < 0.01                     < 0.005
//   intermediate  0.01 - 1                   0.005 - 0.05
//   tactical      1 - 10                     0.05 - 0.5
//   consumer      10 - 1000                  > 0.5
//
// The verdict uses the bias instability as the lab and datasheets quote it
// (the minimum of the Allan deviation) and the ARW; where they point at
// different classes the worse class wins, and the verdict says which
// criterion decided (docs/conventions.md section 8). Shared by the answer keys of `sim` and the
// estimators.
#pragma once

#include <string_view>

namespace foglab {

/// The manual's Table 1 classes, best first.
enum class AccuracyClass { strategic, navigation, intermediate, tactical, consumer };

/// "strategic", "navigation", "intermediate", "tactical", "consumer".
std::string_view to_string(AccuracyClass c);

/// Class by bias instability [deg/h]: < 0.001 strategic, < 0.01 navigation,
/// 0.01..1 intermediate, (1, 10] tactical, above consumer. A value on a
/// boundary two classes share (1, 10) goes to the better class, so a
/// datasheet's "<= 1 deg/h" is met.
AccuracyClass class_by_bias_instability(double bi_deg_h);

/// Class by angle random walk [deg/sqrt(h)]: < 0.0003 strategic, < 0.005
/// navigation, 0.005..0.05 intermediate, (0.05, 0.5] tactical, above consumer.
AccuracyClass class_by_arw(double arw_deg_sqrt_h);

/// Which Table 1 criterion set the class: both (they agree), or the one
/// that points at the worse class.
enum class ClassCriterion { both, bias_instability, arw };

/// "both", "bias_instability", "arw".
std::string_view to_string(ClassCriterion c);

struct ClassVerdict {
  AccuracyClass accuracy_class = AccuracyClass::consumer;  ///< the worse of the two
  AccuracyClass by_bias_instability = AccuracyClass::consumer;
  AccuracyClass by_arw = AccuracyClass::consumer;
  ClassCriterion decided_by = ClassCriterion::both;
};

/// The Table 1 verdict: the worse of the two classes wins.
ClassVerdict classify(double bi_deg_h, double arw_deg_sqrt_h);

}  // namespace foglab
