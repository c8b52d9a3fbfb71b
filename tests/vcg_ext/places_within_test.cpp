// vcg_ext/places_within.h: PlacesWithin finds exactly the places of the values at most the bound, in
// order, for floats and doubles, any length (the vector steps and the scalar rest), ties and NaN included.
#include <gtest/gtest.h>
#include <cmath>
#include <random>
#include <vector>
#include <vcg_ext/places_within.h>

namespace places_within_test {

template <class T>
void ExpectPlaces(const std::vector<T>& v, T bound) {
  std::vector<int> expected;
  for (size_t c = 0; c < v.size(); ++c)
    if (v[c] <= bound) expected.push_back(int(c));
  std::vector<int> out(v.size() + 3, -1);
  const size_t found = vcg_ext::PlacesWithin(v.data(), v.size(), bound, out.data());
  ASSERT_EQ(found, expected.size());
  EXPECT_EQ(std::vector<int>(out.begin(), out.begin() + long(found)), expected);
}

template <class T>
void EveryLength() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<T> u(0, 1);
  for (size_t n = 0; n <= 37; ++n)
    for (T bound : {T(-1), T(0.25), T(0.5), T(2)}) {
      std::vector<T> v(n);
      for (T& x : v) x = T(std::floor(u(rng) * 8) / 8);  // values equal to the bound too
      if (n > 5) v[3] = T(NAN), v[n - 1] = T(INFINITY);
      ExpectPlaces(v, bound);
    }
}

TEST(PlacesWithin, FloatsOfEveryLengthTiesAndNaN) { EveryLength<float>(); }
TEST(PlacesWithin, DoublesOfEveryLengthTiesAndNaN) { EveryLength<double>(); }

}  // namespace places_within_test
