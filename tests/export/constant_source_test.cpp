// The generator's exact literals, its checksums (against the exported header's own fnv1a) and
// the labels as identifiers.
#include <gtest/gtest.h>

#include <cstdlib>
#include <limits>
#include <vector>

#include "export/constant_source.hpp"
#include "export/controller_export.hpp"
#include "export/onboard/step_common.hpp"

namespace thetad {
namespace {

TEST(ConstantSource, LiteralsReadBackExactly) {
  for (const double value : {0.1, -1.0 / 3.0, 1e-300, 5e-324, 1.7976931348623157e308, -0.0, 86.94})
    EXPECT_EQ(std::strtod(exact_literal(value).c_str(), nullptr), value) << exact_literal(value);
}

TEST(ConstantSource, ChecksumsAreThoseTheHeaderComputes) {
  const std::vector<double> a = {0.1, -2.5, 1e-9}, b = {3.0};
  DesignSource source;
  source.add_array("a", a);
  source.add_array("b", b);
  std::uint64_t hash = thetad_onboard::fnv1a(a.data(), 3, thetad_onboard::kFnvOffset);
  EXPECT_EQ(source.checksum_double(), thetad_onboard::fnv1a(b.data(), 1, hash));
  const float af[] = {0.1f, -2.5f, 1e-9f}, bf[] = {3.0f};
  hash = thetad_onboard::fnv1a(af, 3, thetad_onboard::kFnvOffset);
  EXPECT_EQ(source.checksum_float(), thetad_onboard::fnv1a(bf, 1, hash));
}

TEST(ConstantSource, LabelsBecomeIdentifiers) {
  EXPECT_EQ(identifier_of("theta-d"), "theta_d");
  EXPECT_EQ(identifier_of("3terms"), "c_3terms");
  EXPECT_EQ(identifier_of("lqr"), "lqr");
}

}  // namespace
}  // namespace thetad
