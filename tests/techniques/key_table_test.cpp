// technique_api/key_table.h: a key bound once to its field gives the parameter list, the reading of
// a run's Settings and the writing back, with the field's initial value as the default.
#include <gtest/gtest.h>

#include "technique_api/key_table.h"

namespace aor {
namespace {

enum class Mode { First, Second, Third };

struct ToySettings {
  float radius = 0.75f;
  float strength = 0.3f;
  int taps = 5;
  bool blur = true;
  Mode mode = Mode::Second;
};

const KeyTable<ToySettings>& toyKeys() {
  using T = ToySettings;
  static const KeyTable<T> table = {
      radiusKey(&T::radius),
      floatKey(&T::strength, "strength", 0.0, 2.0, "how strong", kTunable),
      intKey(&T::taps, "taps", 1, 9, "how many"),
      boolKey(&T::blur, "blur", "blur or not"),
      enumKey(&T::mode, "mode", {"first", "second", "third"}, "which"),
  };
  return table;
}

const Technique& toyTechnique() {
  static const Technique t = [] {
    Technique technique;
    technique.name = "toy";
    technique.parameters = toyKeys().parameters();
    return technique;
  }();
  return t;
}

TEST(KeyTable, DefaultsTypesAndRangesComeFromTheFieldsAndTheDeclarations) {
  const auto& p = toyTechnique().parameters;
  ASSERT_EQ(p.size(), 5u);
  EXPECT_EQ(p[0].key, kRadiusKey);
  EXPECT_EQ(p[0].defaultValue, 0.75);
  EXPECT_EQ(p[1].type, ParameterType::Float);
  EXPECT_EQ(p[1].defaultValue, double(0.3f));  // the float the shaders get
  EXPECT_TRUE(p[1].tunable);
  EXPECT_EQ(p[1].max, 2.0);
  EXPECT_EQ(p[2].type, ParameterType::Int);
  EXPECT_EQ(p[2].defaultValue, 5.0);
  EXPECT_FALSE(p[2].tunable);
  EXPECT_EQ(p[3].type, ParameterType::Bool);
  EXPECT_EQ(p[3].defaultValue, 1.0);
  EXPECT_EQ(p[4].type, ParameterType::Enum);
  EXPECT_EQ(p[4].defaultValue, 1.0);
  EXPECT_EQ(p[4].max, 2.0);
  EXPECT_EQ(valueText(p[4], p[4].defaultValue), "second");
}

TEST(KeyTable, ReadsWhatTheUserSetIntoEachField) {
  Settings s(toyTechnique());
  s.assign("strength=1.5");
  s.assign("taps=8");
  s.assign("blur=0");
  s.assign("mode=third");
  s.assign("radius=2");
  ToySettings t = toyKeys().read(s);
  EXPECT_EQ(t.strength, 1.5f);
  EXPECT_EQ(t.taps, 8);
  EXPECT_FALSE(t.blur);
  EXPECT_EQ(t.mode, Mode::Third);
  EXPECT_EQ(t.radius, 2.0f);
}

TEST(KeyTable, WritesFieldsBackSoThatReadingGivesThemAgain) {
  ToySettings values;
  values.strength = 0.125f;
  values.taps = 2;
  values.blur = false;
  values.mode = Mode::First;
  Settings s = toyKeys().write(toyTechnique(), values);
  EXPECT_EQ(s.text("mode"), "first");
  EXPECT_EQ(s.i("taps"), 2);
  ToySettings back = toyKeys().read(s);
  EXPECT_EQ(back.strength, values.strength);
  EXPECT_EQ(back.taps, values.taps);
  EXPECT_EQ(back.blur, values.blur);
  EXPECT_EQ(back.mode, values.mode);
}

TEST(KeyTable, KeysAnotherTechniqueLacksKeepTheFieldsInitialValues) {
  Technique partial;
  partial.name = "partial";
  partial.parameters = {toyTechnique().parameters[2]};  // taps only
  Settings s(partial);
  s.assign("taps=9");
  ToySettings t = toyKeys().read(s);
  EXPECT_EQ(t.taps, 9);
  EXPECT_EQ(t.strength, ToySettings{}.strength);
  EXPECT_EQ(t.mode, ToySettings{}.mode);
  Settings written = toyKeys().write(partial, ToySettings{});
  EXPECT_EQ(written.i("taps"), 5);
}

}  // namespace
}  // namespace aor
