#include "foglab/core/accuracy_class.h"

#include <algorithm>

namespace foglab {

std::string_view to_string(AccuracyClass c) {
  switch (c) {
    case AccuracyClass::strategic: return "strategic";
    case AccuracyClass::navigation: return "navigation";
    case AccuracyClass::intermediate: return "intermediate";
    case AccuracyClass::tactical: return "tactical";
    case AccuracyClass::consumer: return "consumer";
  }
  return "consumer";
}

std::string_view to_string(ClassCriterion c) {
  switch (c) {
    case ClassCriterion::both:
      return "both";
    case ClassCriterion::bias_instability:
      return "bias_instability";
    case ClassCriterion::arw:
      return "arw";
  }
  return "both";
}

AccuracyClass class_by_bias_instability(double bi_deg_h) {
  if (bi_deg_h < 0.001) return AccuracyClass::strategic;
  if (bi_deg_h < 0.01) return AccuracyClass::navigation;
  if (bi_deg_h <= 1.0) return AccuracyClass::intermediate;
  if (bi_deg_h <= 10.0) return AccuracyClass::tactical;
  return AccuracyClass::consumer;
}

AccuracyClass class_by_arw(double arw_deg_sqrt_h) {
  if (arw_deg_sqrt_h < 0.0003) return AccuracyClass::strategic;
  if (arw_deg_sqrt_h < 0.005) return AccuracyClass::navigation;
  if (arw_deg_sqrt_h <= 0.05) return AccuracyClass::intermediate;
  if (arw_deg_sqrt_h <= 0.5) return AccuracyClass::tactical;
  return AccuracyClass::consumer;
}

ClassVerdict classify(double bi_deg_h, double arw_deg_sqrt_h) {
  ClassVerdict v;
  v.by_bias_instability = class_by_bias_instability(bi_deg_h);
  v.by_arw = class_by_arw(arw_deg_sqrt_h);
  v.accuracy_class = std::max(v.by_bias_instability, v.by_arw);
  v.decided_by = v.by_bias_instability == v.by_arw  ? ClassCriterion::both
                 : v.by_bias_instability > v.by_arw ? ClassCriterion::bias_instability
                                                    : ClassCriterion::arw;
  return v;
}

}  // namespace foglab
