#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/stats/tau_grid.h"

namespace foglab::stats {
namespace {

using Factors = std::vector<std::int64_t>;

TEST(TauGrid, OctaveKeepsTenClustersLikeTheLabManual) {
  // 1001 phase points = 1000 rate samples: floor(1000 / m) >= 10 -> m <= 100.
  EXPECT_EQ(averaging_factors(parse_tau_grid("octave"), 1001, 1.0, 500),
            (Factors{1, 2, 4, 8, 16, 32, 64}));
  TauGrid relaxed = parse_tau_grid("octave");
  relaxed.min_clusters = 1;
  EXPECT_EQ(averaging_factors(relaxed, 1001, 1.0, 500),
            (Factors{1, 2, 4, 8, 16, 32, 64, 128, 256}));
}

TEST(TauGrid, DecadeIsOneTwoFourPerDecadeAsStable32) {
  TauGrid grid = parse_tau_grid("decade");
  grid.min_clusters = 1;
  EXPECT_EQ(averaging_factors(grid, 1001, 1.0, 500), (Factors{1, 2, 4, 10, 20, 40, 100, 200, 400}));
}

TEST(TauGrid, NPerDecadeRoundsAndRemovesDuplicates) {
  const TauGrid grid = parse_tau_grid("5-per-decade");
  EXPECT_EQ(grid.per_decade, 5);
  EXPECT_EQ(averaging_factors(grid, 10001, 1.0, 5000),
            (Factors{1, 2, 3, 4, 6, 10, 16, 25, 40, 63, 100, 158, 251, 398, 631, 1000}));
}

TEST(TauGrid, AllIsEveryFactorButBounded) {
  EXPECT_EQ(averaging_factors(parse_tau_grid("all"), 101, 1.0, 50).size(), 10u);
  EXPECT_EQ(averaging_factors(parse_tau_grid("all"), 1000001, 1.0, 500000).size(),
            static_cast<std::size_t>(kAllGridMaxFactors));
  // 10^8 points: the work bound allows 2e10 / 1e8 = 200 factors.
  EXPECT_EQ(averaging_factors(parse_tau_grid("all"), 100000001, 1.0, 50000000).size(), 199u);
}

TEST(TauGrid, ExplicitListIsHonouredInSecondsAtTheSampleRate) {
  const TauGrid grid = parse_tau_grid("0.5, 1,10");
  EXPECT_EQ(grid.kind, TauGridKind::list);
  // At 100 Hz: 50, 100, 1000 samples; only 5 clusters at 10 s, still honoured.
  EXPECT_EQ(averaging_factors(grid, 5001, 100.0, 2500), (Factors{50, 100, 1000}));
  EXPECT_EQ(to_string(grid), "0.5,1,10");
}

TEST(TauGrid, BadSpecificationsNameTheProblem) {
  try {
    parse_tau_grid("1,x,3");
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("'x' is not a number"), std::string::npos);
  }
  try {
    parse_tau_grid("1,-2");
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("tau -2 s is not positive"), std::string::npos);
  }
  EXPECT_THROW(parse_tau_grid("0"), UsageError);
  EXPECT_THROW(parse_tau_grid("0-per-decade"), UsageError);
  EXPECT_THROW(parse_tau_grid(""), UsageError);
  try {
    averaging_factors(parse_tau_grid("0.001"), 1001, 100.0, 500);
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("shorter than the sample interval"), std::string::npos);
  }
  EXPECT_THROW(averaging_factors(parse_tau_grid("600"), 1001, 1.0, 500), DataError);
  TauGrid zero = parse_tau_grid("octave");
  zero.min_clusters = 0;
  EXPECT_THROW(averaging_factors(zero, 1001, 1.0, 500), UsageError);
}

}  // namespace
}  // namespace foglab::stats
