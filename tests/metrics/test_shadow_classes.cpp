// Lit / penumbra / umbra classes and their confusion matrix
// (metrics/shadow_classes.h), and the record's reading of it, on images
// whose counts are known by construction.
#include <gtest/gtest.h>

#include <stdexcept>

#include "metrics/shadow_classes.h"
#include "record/classes_record.h"

namespace sb::metrics {

using core::ImageF;
using record::ClassesRecord;

namespace {

TEST(ShadowClasses, ThresholdsAreThePenumbraMasksEps) {
  EXPECT_EQ(shadow_class(0.0f), ShadowClass::Umbra);
  EXPECT_EQ(shadow_class(1e-6f), ShadowClass::Umbra);
  EXPECT_EQ(shadow_class(2e-6f), ShadowClass::Penumbra);
  EXPECT_EQ(shadow_class(0.5f), ShadowClass::Penumbra);
  EXPECT_EQ(shadow_class(1.0f - 2e-6f), ShadowClass::Penumbra);
  EXPECT_EQ(shadow_class(1.0f), ShadowClass::Lit);
}

// A hard shadow against a soft reference: every reference penumbra pixel
// is missed, none invented; masked pixels are not counted.
TEST(ShadowClasses, AHardShadowMissesThePenumbraAndInventsNone) {
  // Reference row: 0 0 .25 .5 .75 1 1 1; technique: 0 0 0 0 1 1 1 1.
  const float ref[8] = {0.0f, 0.0f, 0.25f, 0.5f, 0.75f, 1.0f, 1.0f, 1.0f};
  const float hard[8] = {0.0f, 0.0f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f, 1.0f};
  ImageF r(8, 1, 1), t(8, 1, 1);
  for (int i = 0; i < 8; ++i) {
    r.data[size_t(i)] = ref[i];
    t.data[size_t(i)] = hard[i];
  }
  std::vector<uint8_t> mask(8, 1);
  mask[7] = 0;
  const ClassCounts c = confusion_matrix(t, r, mask);
  // Rows: reference lit, penumbra, umbra; columns: the technique's.
  EXPECT_EQ(c[0][0], 2);  // pixels 5, 6 (7 masked)
  EXPECT_EQ(c[1][2], 2);  // .25 and .5 read as umbra
  EXPECT_EQ(c[1][0], 1);  // .75 read as lit
  EXPECT_EQ(c[2][2], 2);
  EXPECT_EQ(c[1][1] + c[0][1] + c[2][1], 0);
  const ClassesRecord record{c};
  EXPECT_DOUBLE_EQ(*record.penumbra_missed(), 1.0);
  EXPECT_FALSE(record.penumbra_invented());  // the technique has no penumbra pixel
}

TEST(ShadowClasses, OuterPenumbraInventsWhatTheReferenceCallsLit) {
  ImageF r(4, 1, 1), t(4, 1, 1);
  r.data = {0.0f, 0.5f, 1.0f, 1.0f};
  t.data = {0.0f, 0.2f, 0.6f, 1.0f};
  const ClassesRecord record{confusion_matrix(t, r, std::vector<uint8_t>(4, 1))};
  EXPECT_DOUBLE_EQ(*record.penumbra_missed(), 0.0);
  EXPECT_DOUBLE_EQ(*record.penumbra_invented(), 0.5);  // of 2 penumbra pixels, 1 is lit
}

TEST(ShadowClasses, ShapesMustAgree) {
  ImageF a(4, 1, 1), b(3, 1, 1);
  EXPECT_THROW(confusion_matrix(a, b, std::vector<uint8_t>(4, 1)), std::invalid_argument);
  EXPECT_THROW(confusion_matrix(a, a, std::vector<uint8_t>(3, 1)), std::invalid_argument);
}

}  // namespace
}  // namespace sb::metrics
