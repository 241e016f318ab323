// sao-bench --tune's time unit (samples/bench/tune_time.h) on synthetic rows: a row is divided by
// its own session's anchors only, interpolated by candidate index, the nearest where they lie on
// one side; a session without anchors is refused naming the row.
#include <gtest/gtest.h>

#include <vector>

#include "tune_time.h"

namespace sao::bench {
namespace {

TimedRow anchor(std::size_t candidate, std::uint32_t session, std::vector<double> ms) {
  return {"anchor medium-" + std::to_string(candidate), candidate, session, true, std::move(ms)};
}

TimedRow row(const std::string& label, std::size_t candidate, std::uint32_t session, std::vector<double> ms) {
  return {label, candidate, session, false, std::move(ms)};
}

void expectNear(const std::vector<double>& got, const std::vector<double>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t s = 0; s < got.size(); ++s) EXPECT_NEAR(got[s], want[s], 1e-9 * want[s]) << "scene " << s;
}

std::vector<std::vector<double>> units(const std::vector<TimedRow>& rows) {
  std::vector<std::vector<double>> out;
  const Status s = timeUnits(rows, out);
  EXPECT_TRUE(s.ok()) << s.message;
  EXPECT_EQ(out.size(), rows.size());
  out.resize(rows.size());  // a failure then shows as empty units, not as a crash
  return out;
}

TEST(TuneTime, ASessionsRowIsDividedByItsOwnAnchorsOnly) {
  // Session 1 ran on a machine 10x slower: its anchors at 4 and 6 took 100 ms a scene. Session 2
  // measured candidate 5, between session 1's anchors, and its own anchors at 0 and 10 (10 ms).
  const std::vector<TimedRow> rows = {
      anchor(4, 1, {100, 100}), row("grid old", 3, 1, {50, 50}),    anchor(6, 1, {100, 100}),
      anchor(0, 2, {10, 10}),   row("preset new", 5, 2, {5, 5}),   anchor(10, 2, {10, 10}),
  };
  const auto u = units(rows);
  expectNear(u[1], {100, 100});  // session 1's row, before its first anchor: that anchor, 0.5x
  expectNear(u[4], {10, 10});    // session 2's row: 0.5x too, not 0.05x from session 1's anchors
}

TEST(TuneTime, InterpolatesLinearlyByCandidateIndexPerScene) {
  const std::vector<TimedRow> rows = {anchor(0, 1, {10, 40}), anchor(10, 1, {20, 80}), row("grid", 3, 1, {1, 1})};
  const auto u = units(rows);
  expectNear(u[2], {13, 52});
}

TEST(TuneTime, UsesTheNearestAnchorWhereTheSessionHasThemOnOneSideOnly) {
  // Session 2 measured anchors at 10 and 20 only; session 1's anchor at 0 must not be used for row 5.
  const std::vector<TimedRow> rows = {anchor(0, 1, {1000}),  anchor(10, 2, {10}),      anchor(20, 2, {30}),
                                      row("before", 5, 2, {1}), row("after", 25, 2, {1})};
  const auto u = units(rows);
  expectNear(u[3], {10});
  expectNear(u[4], {30});
}

TEST(TuneTime, AnAnchorIsItsOwnUnit) {
  const std::vector<TimedRow> rows = {anchor(0, 1, {10}), anchor(10, 1, {30})};
  const auto u = units(rows);
  expectNear(u[0], {10});
  expectNear(u[1], {30});
}

TEST(TuneTime, ASessionWithoutAnchorsIsAnErrorNamingTheRow) {
  const std::vector<TimedRow> rows = {anchor(0, 1, {10}), anchor(10, 1, {10}), row("preset high", 5, 2, {5})};
  std::vector<std::vector<double>> u;
  const Status s = timeUnits(rows, u);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.code, StatusCode::InvalidInput);
  EXPECT_NE(s.message.find("preset high"), std::string::npos) << s.message;
  EXPECT_NE(s.message.find("session 2"), std::string::npos) << s.message;
}

TEST(TuneTime, RefusesAnAnchorWithoutTimeAndTwoAnchorsAtOneIndexOfOneSession) {
  std::vector<std::vector<double>> u;
  const Status noTime = timeUnits({anchor(0, 1, {10, 0}), row("grid", 1, 1, {1, 1})}, u);
  ASSERT_FALSE(noTime.ok());
  EXPECT_NE(noTime.message.find("anchor medium-0"), std::string::npos) << noTime.message;
  EXPECT_FALSE(timeUnits({anchor(0, 1, {10}), anchor(0, 1, {11})}, u).ok());
  EXPECT_TRUE(timeUnits({anchor(0, 1, {10}), anchor(0, 2, {11})}, u).ok());  // one per session
}

TEST(TuneTime, DriftIsPerSessionOverItsFirstAnchorInCandidateOrder) {
  // Rows in file order, not candidate order: session 2's first anchor (index 0) comes last.
  const std::vector<TimedRow> rows = {anchor(0, 1, {10, 10}),  anchor(10, 1, {6, 6}),  anchor(20, 1, {25, 25}),
                                      anchor(10, 2, {1, 1}),   anchor(0, 2, {2, 2}),   row("grid", 5, 2, {9, 9})};
  const std::vector<SessionDrift> d = anchorDrift(rows);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].session, 1u);
  EXPECT_EQ(d[0].anchors, 3u);
  EXPECT_DOUBLE_EQ(d[0].min, 0.6);
  EXPECT_DOUBLE_EQ(d[0].max, 2.5);
  EXPECT_EQ(d[1].session, 2u);
  EXPECT_EQ(d[1].anchors, 2u);
  EXPECT_DOUBLE_EQ(d[1].min, 0.5);
  EXPECT_DOUBLE_EQ(d[1].max, 1);
}

}  // namespace
}  // namespace sao::bench
