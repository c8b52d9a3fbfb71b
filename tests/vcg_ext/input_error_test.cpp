// vcg_ext/input_error.h: InputError carries its field and its predicate, NonFiniteCoordinates' wording, FieldId,
// Shown's numbers.
#include <gtest/gtest.h>
#include <cmath>
#include <cstdlib>
#include <limits>
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
  EXPECT_STREQ(many.what(), "holds 1,234,567 points with NaN or infinite coordinates");
}

TEST(InputError, CountsAreGroupedByThousands) {
  // As the Python front end and the command count (f"{n:,}"): a layer's millions read at a glance.
  EXPECT_EQ(vcg_ext::Counted(0), "0");
  EXPECT_EQ(vcg_ext::Counted(999), "999");
  EXPECT_EQ(vcg_ext::Counted(1000), "1,000");
  EXPECT_EQ(vcg_ext::Counted(3595), "3,595");
  EXPECT_EQ(vcg_ext::Counted(100000), "100,000");
  EXPECT_EQ(vcg_ext::Counted(14000001), "14,000,001");
  EXPECT_EQ(vcg_ext::Counted(size_t(-1)), "18,446,744,073,709,551,615");
}

TEST(InputError, NumbersAreShownAsTheyWereGiven) {
  EXPECT_EQ(vcg_ext::Shown(0), "0");
  EXPECT_EQ(vcg_ext::Shown(-2), "-2");
  EXPECT_EQ(vcg_ext::Shown(1e9), "1000000000");  // a count in full
  EXPECT_EQ(vcg_ext::Shown(0.05), "0.05");
  EXPECT_EQ(vcg_ext::Shown(-1e-9), "-1e-09");     // not six decimals' "-0.000000"
  EXPECT_EQ(vcg_ext::Shown(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(vcg_ext::Shown(1e19), "1e+19");
  EXPECT_EQ(vcg_ext::Shown(double(-1e-9f)), "-1e-09");  // a float parameter's value, as its user gave it
  EXPECT_EQ(vcg_ext::Shown(double(1e19f)), "1e+19");
  for (double x : {1.0 / 3, 123456.789, -7.25e-300, 4.9e-324, 1.7976931348623157e308})
    EXPECT_EQ(std::strtod(vcg_ext::Shown(x).c_str(), nullptr), x) << vcg_ext::Shown(x);
  EXPECT_EQ(vcg_ext::Shown(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(vcg_ext::Shown(std::nan("")), "nan");
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
