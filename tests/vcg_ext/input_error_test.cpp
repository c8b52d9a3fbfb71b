// vcg_ext/input_error.h: InputError carries its field and its predicate, NonFiniteCoordinates' wording, FieldId.
#include <gtest/gtest.h>
#include <set>
#include <stdexcept>
#include <string>
#include <vcg_ext/input_error.h>

namespace input_error_test {

using vcg_ext::Field;

TEST(InputError, IsAnInvalidArgumentCarryingItsFieldAndPredicate) {
  // Front ends catch std::invalid_argument for bad input, and word the field with their own names.
  try {
    throw vcg_ext::InputError(Field::Radius, "must be a positive number (got 0)");
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "must be a positive number (got 0)");
    const auto* input = dynamic_cast<const vcg_ext::InputError*>(&e);
    ASSERT_NE(input, nullptr);
    EXPECT_EQ(input->field, Field::Radius);
  }
  const vcg_ext::InputError copy = vcg_ext::InputError(Field::Levels, "x");
  EXPECT_EQ(copy.field, Field::Levels);
  EXPECT_STREQ(copy.what(), "x");
}

TEST(InputError, NonFiniteCoordinatesCountsThePointsInOneWording) {
  const vcg_ext::InputError one = vcg_ext::NonFiniteCoordinates(1);
  EXPECT_EQ(one.field, Field::Coordinates);
  EXPECT_STREQ(one.what(), "holds 1 point with NaN or infinite coordinates");
  const vcg_ext::InputError many = vcg_ext::NonFiniteCoordinates(1234567);
  EXPECT_EQ(many.field, Field::Coordinates);
  EXPECT_STREQ(many.what(), "holds 1234567 points with NaN or infinite coordinates");
}

TEST(InputError, EveryFieldHasItsOwnId) {
  // The ids are what front ends pass the error on by (the Python package maps them to its
  // argument names): every field needs one, and no two fields may share one.
  const int last = int(Field::Separation);  // the enum's last field; they are numbered from 0
  std::set<std::string> ids;
  for (int f = 0; f <= last; ++f) {
    const std::string id = vcg_ext::FieldId(Field(f));
    EXPECT_NE(id, "Unknown") << "field " << f;
    EXPECT_FALSE(id.empty()) << "field " << f;
    ids.insert(id);
  }
  EXPECT_EQ(ids.size(), size_t(last + 1));
  EXPECT_STREQ(vcg_ext::FieldId(Field::SampleNum), "SampleNum");
  EXPECT_STREQ(vcg_ext::FieldId(Field::Coordinates), "Coordinates");
  EXPECT_STREQ(vcg_ext::FieldId(Field(last + 1)), "Unknown") << "a value past the enum";
}

}  // namespace input_error_test
