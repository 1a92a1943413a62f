// The laboratory's cells and shards (lab/cells.h): results survive JSON
// exactly, the shards of a sweep partition its cells, and a replay of the
// shards hands every cell its computed result; --shard values are checked.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "lab/cells.h"
#include "lab/scan.h"

using namespace lab;

namespace {

std::string scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("particle-lab-cells-" + name);
  std::filesystem::remove_all(dir);
  return dir.string();
}

bool sameBits(double a, double b) { return std::isnan(a) ? std::isnan(b) : a == b && std::signbit(a) == std::signbit(b); }

}  // namespace

TEST(CellJson, EveryDoubleReadsBackExactly) {
  std::vector<double> values = {0.0, -0.0, 1e-320, -4.9e-324, 0.1, 1.0 / 3.0, 1e308, -1e-300,
                                std::numeric_limits<double>::quiet_NaN(), HUGE_VAL, -HUGE_VAL};
  std::mt19937_64 bits(16);
  for (int k = 0; k < 20000; ++k) {
    const std::uint64_t b = bits();
    double v;
    std::memcpy(&v, &b, sizeof v);
    values.push_back(v);
  }
  // Through the text a shard writes and a merge reads.
  const Json text = Json::parse(encode(values).dump());
  std::vector<double> back;
  decode(text, back);
  ASSERT_EQ(back.size(), values.size());
  for (std::size_t k = 0; k < values.size(); ++k) EXPECT_TRUE(sameBits(values[k], back[k])) << values[k];
}

TEST(CellJson, StructsKeepTheirFields) {
  Boundary b;
  b.safeDt = 0.0625, b.firstFailureDt = std::nan(""), b.firstFailure = Failure::ConstraintViolation;
  b.survivalAbove = {0.1, 0.2}, b.lowest = 1e-3, b.highest = HUGE_VAL;
  Boundary back;
  decode(Json::parse(encode(std::pair{b, 3.5}).dump()).at(0), back);
  EXPECT_EQ(back.safeDt, b.safeDt);
  EXPECT_TRUE(std::isnan(back.firstFailureDt));
  EXPECT_EQ(back.firstFailure, Failure::ConstraintViolation);
  EXPECT_EQ(back.survivalAbove, b.survivalAbove);
  EXPECT_EQ(back.highest, HUGE_VAL);
}

TEST(Shards, PartitionTheCellsAndReplayThem) {
  const int shards = 3;
  const std::size_t count = 20;
  std::vector<int> computed(count, 0);
  std::vector<std::string> dirs;
  for (int k = 1; k <= shards; ++k) {
    LabOptions options;
    options.jobs = 2;
    dirs.push_back(scratch("shard" + std::to_string(k)));
    options.cells = std::make_shared<Cells>(ShardSpec{k, shards}, dirs.back());
    // A sweep then a sequential cell: indices 0..count-1, then count.
    std::set<std::size_t> delivered;
    sweep<double>(
        options, count,
        [&](std::size_t i) -> std::optional<double> {
          ++computed[i];
          return 1.0 / (1.0 + static_cast<double>(i));
        },
        [&](std::size_t i, double&) { delivered.insert(i); });
    const auto last = cell<long>(options, [] { return std::optional<long>(42); });
    EXPECT_FALSE(options.cells->writesOutputs());
    for (std::size_t i = 0; i < count; ++i) EXPECT_EQ(delivered.count(i), i % shards == std::size_t(k - 1) ? 1u : 0u);
    EXPECT_EQ(last.has_value(), count % shards == std::size_t(k - 1));
    options.cells->writeManifest("test", {"test", "--quick"});
  }
  for (std::size_t i = 0; i < count; ++i) EXPECT_EQ(computed[i], 1) << "cell " << i;

  const ShardSet set = readShards(dirs);
  EXPECT_EQ(set.cellCount, count + 1);
  LabOptions replay;
  replay.cells = std::make_shared<Cells>(set.cells);
  std::vector<double> results(count, 0.0);
  sweep<double>(
      replay, count, [](std::size_t) -> std::optional<double> { throw std::logic_error("computed in a replay"); },
      [&](std::size_t i, double& r) { results[i] = r; });
  for (std::size_t i = 0; i < count; ++i) EXPECT_EQ(results[i], 1.0 / (1.0 + static_cast<double>(i)));
  EXPECT_EQ(cell<long>(replay, [] { return std::optional<long>(); }), 42);
  EXPECT_TRUE(replay.cells->writesOutputs());

  // Two shards of three are an incomplete set; a shard twice is refused.
  EXPECT_THROW(readShards({dirs[0], dirs[1]}), std::invalid_argument);
  EXPECT_THROW(readShards({dirs[0], dirs[0], dirs[1], dirs[2]}), std::invalid_argument);
  for (const auto& dir : dirs) std::filesystem::remove_all(dir);
}

TEST(Shards, ParseShardAcceptsOnlyKOfN) {
  const ShardSpec spec = parseShard("2/5");
  EXPECT_EQ(spec.index, 2);
  EXPECT_EQ(spec.count, 5);
  EXPECT_EQ(parseShard("1/1").count, 1);
  for (const char* bad : {"0/2", "3/2", "1/0", "junk", "1/2/3", "/2", "1/", "-1/2", "+1/2", "01/2", "1 /2", ""})
    EXPECT_THROW(parseShard(bad), std::invalid_argument) << bad;
}
