// The report's text held against its data (lab/text_checks.h): the three
// contradictions of the report as issue 46 found it fail on that day's data
// (tests/data/report_checks), their replacements pass, and each kind of
// declared check can fail.
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "lab/render.h"
#include "lab/text_checks.h"

using namespace lab;

namespace {

const std::string kChecks = REPORT_CHECKS_DIR;
const std::string kData = kChecks + "/data";

std::string fileText(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The contradictions a template's rendering reports against the fixture data (none: empty).
std::vector<std::string> contradictions(const std::string& text) {
  try {
    renderTemplate(text, kData);
  } catch (const ReportContradiction& e) {
    return e.found;
  }
  return {};
}

}  // namespace

TEST(TextChecks, NeverExplicitEulerFailsWhileTheCostExperimentPicksIt) {
  const auto found = contradictions(fileText(kChecks + "/never-euler.md"));
  ASSERT_EQ(found.size(), 1u);
  EXPECT_NE(found[0].find("never explicit euler"), std::string::npos) << found[0];
  EXPECT_NE(found[0].find("cost_vs_size.csv"), std::string::npos) << found[0];
  // The same words about a scheme the data never picks hold; so does "never" before other words.
  EXPECT_TRUE(contradictions("Never xpbd at dt 1. The matrix is never formed.\n").empty());
  EXPECT_EQ(contradictions("never `euler` here\n").size(), 1u);
}

TEST(TextChecks, TheDampingSentenceFailsAgainstTheLongtimeData) {
  const auto found = contradictions(fileText(kChecks + "/damping.md"));
  ASSERT_EQ(found.size(), 1u);  // the pendulum's loss grows with dt; the chain's does not
  EXPECT_NE(found[0].find("chain6_loss is not increasing in dt"), std::string::npos) << found[0];
  EXPECT_NE(found[0].find("template line 2"), std::string::npos) << found[0];
}

TEST(TextChecks, ASafeStepWithoutItsBoundFails) {
  const auto found = contradictions(fileText(kChecks + "/safe-dt.md"));
  ASSERT_EQ(found.size(), 2u);
  EXPECT_NE(found[0].find("\"safe dt\""), std::string::npos) << found[0];
  EXPECT_NE(found[1].find("certified safe steps (table 2)"), std::string::npos) << found[1];
  EXPECT_TRUE(contradictions("The largest safe dt is 0.07 (p ≤ 0.0013).\n").empty());
}

TEST(TextChecks, TheReplacementsHoldOnTheSameData) {
  EXPECT_TRUE(contradictions(fileText(kChecks + "/fixed.md")).empty());
}

TEST(TextChecks, EachKindOfCheckCanFail) {
  // The coarse scan: rk4 at cl 80 fails by the constraint criterion, midpoint by energy.
  EXPECT_EQ(evaluateCheck("some stability_boundary.csv integrator=rk4 chain_length=80 first_failure=constraint", kData), "");
  EXPECT_NE(evaluateCheck("some stability_boundary.csv integrator=midpoint chain_length=80 first_failure=constraint", kData), "");
  EXPECT_EQ(evaluateCheck("never stability_boundary.csv integrator=implicit-euler first_failure=energy", kData), "");
  EXPECT_NE(evaluateCheck("never stability_boundary.csv integrator=rk4 first_failure=energy", kData), "");
  // every: a column against a column, and against a number, over the rows meeting a condition.
  EXPECT_EQ(evaluateCheck("every stability_boundary.csv safe_dt < first_failure_dt first_failure_dt>0", kData), "");
  EXPECT_NE(evaluateCheck("every stability_boundary.csv safe_dt < 0.1", kData), "");
  EXPECT_EQ(evaluateCheck("decreasing longtime_implicit_loss.csv dt swing_energy_left", kData), "");
  EXPECT_NE(evaluateCheck("increasing longtime_implicit_loss.csv dt swing_energy_left", kData), "");
  // value: with a factor, and a value that is not a number.
  EXPECT_EQ(evaluateCheck("value stability.survived_dt.rk4.cl24 > 0.04", kData), "");
  EXPECT_NE(evaluateCheck("value stability.survived_dt.rk4.cl24 > 2*stability.survived_dt.rk4.cl24", kData), "");
  EXPECT_EQ(evaluateCheck("value stability.bound.rk4.cl24 < 0.002", kData), "");  // "p ≤ 0.0013" reads 0.0013
  EXPECT_EQ(evaluateCheck("value stability.survived_dt.xpbd.cl24 > 10*stability.survived_dt.rk4.cl24", kData), "");
  EXPECT_THROW(evaluateCheck("value cost.where_cheapest.euler > 1", kData), std::runtime_error);  // words, no number
  EXPECT_THROW(evaluateCheck("value longtime.implicit_chain_trend > 1", kData), std::runtime_error);
  // Malformed checks and missing files or columns are errors, not passes.
  EXPECT_THROW(evaluateCheck("sometimes x.csv", kData), std::runtime_error);
  EXPECT_THROW(evaluateCheck("never nosuch.csv a=b", kData), std::runtime_error);
  EXPECT_THROW(evaluateCheck("never stability_boundary.csv nosuch=1", kData), std::runtime_error);
  EXPECT_THROW(evaluateCheck("never ../data/values.csv key=x", kData), std::runtime_error);
  EXPECT_THROW(evaluateCheck("every stability_boundary.csv safe_dt", kData), std::runtime_error);
}
