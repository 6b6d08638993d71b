// What a solve tells the user when light goes missing (solve/Diagnosis.h).

#include "solve/Diagnosis.h"

#include <gtest/gtest.h>

namespace rad {
namespace {

TEST(Diagnosis, LightLostPastTheThresholdIsSaid) {
    EnergyBalance e;
    e.emitted = 2.0;
    e.lost = 0.1;  // 5%: what coarse links leave, said in the report's balance only
    EXPECT_TRUE(lostLightWarnings(e, 0.1).empty());
    e.lost = 0.6;  // 30%: a lamp under a ceiling, say
    const std::vector<Warning> w = lostLightWarnings(e, 0.1);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0].kind, "lost_light");
    EXPECT_DOUBLE_EQ(w[0].amount, 0.3);
    EXPECT_NE(w[0].message.find("30% of the emitted light is lost"), std::string::npos)
        << w[0].message;
    e.emitted = 0.0;  // nothing emits: nothing to say here
    EXPECT_TRUE(lostLightWarnings(e, 0.1).empty());
}

}  // namespace
}  // namespace rad
