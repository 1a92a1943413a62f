// The laboratory's cells and shards (lab/cells.h): results survive JSON
// exactly, the shards of a sweep partition its cells, and a replay of the
// shards hands every cell its computed result; --shard values are checked.
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <typeinfo>
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

// A recorded value of the wrong JSON type or shape is refused with its place
// in the result and what was found there, in the program's words (never
// nlohmann's "[json.exception...]"), and never read as a nearby value: a
// pair of three values, an integer written 1.5 or past its type, an object
// with a field too many.
TEST(CellJson, ValuesOfTheWrongShapeAreRefusedWithTheirPlace) {
  const auto refusal = [](const char* text, auto value) -> std::string {
    try {
      decode(Json::parse(text), value);
    } catch (const CellShapeError& e) {
      return e.what();
    }
    return "read back";
  };
  using Samples = std::vector<std::pair<double, double>>;
  EXPECT_EQ(refusal("[[0,1],[1,2,3]]", Samples{}), "$[1]: expected an array of 2 values, got [1,2,3]");
  EXPECT_EQ(refusal("[[0,1],[1]]", Samples{}), "$[1]: expected an array of 2 values, got [1]");
  EXPECT_EQ(refusal("{\"a\":[0,1]}", Samples{}), "$: expected an array, got {\"a\":[0,1]}");
  EXPECT_EQ(refusal("[[0,\"many\"]]", Samples{}), "$[0][1]: expected a number (or \"nan\", \"inf\", \"-inf\"), got \"many\"");
  EXPECT_EQ(refusal("1.5", int{}), "$: expected an integer in [-2147483648, 2147483647], got 1.5");
  EXPECT_EQ(refusal("3000000000", int{}), "$: expected an integer in [-2147483648, 2147483647], got 3000000000");
  EXPECT_EQ(refusal("\"no\"", bool{}), "$: expected true or false, got \"no\"");
  EXPECT_EQ(refusal("7", std::string{}), "$: expected a string, got 7");

  Boundary b;
  b.safeDt = 0.0625, b.firstFailureDt = 0.125, b.survivalAbove = {0.1, 0.2};
  const Json good = encode(b);
  Json missing = good, extra = good, inner = good;
  missing.erase("lowest");
  extra["note"] = "added";
  inner["survival_above"][1] = Json::array({1, 2});
  EXPECT_EQ(refusal(missing.dump().c_str(), Boundary{}), "$: no field 'lowest'");
  EXPECT_EQ(refusal(extra.dump().c_str(), Boundary{}).substr(0, 33), "$: expected an object of 6 fields");
  EXPECT_EQ(refusal(inner.dump().c_str(), Boundary{}), "$.survival_above[1]: expected a number, got [1,2]");
  EXPECT_EQ(refusal(good.dump().c_str(), Boundary{}), "read back");
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

namespace {

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

// One random edit of a shard file's text: a byte changed, a range deleted, a
// hostile token inserted or put in place of a number, the text cut short,
// or a line repeated.
std::string mutate(std::string text, std::mt19937& rng) {
  static const std::vector<std::string> tokens = {
      "-1", "1e999", "NaN", "null", "\"x\"", "[]", "{}", "18446744073709551616", "-0", "1.5", std::string(1, '\0'),
      "\xe2\x80\xae", ",", "]", "}", "\"", "{\"cell\":0,\"result\":1}", "99999999999", "\"shard.json\"", "true"};
  const auto pick = [&](std::size_t n) { return n == 0 ? std::size_t(0) : std::size_t(rng() % n); };
  switch (pick(6)) {
    case 0:
      if (!text.empty()) text[pick(text.size())] = static_cast<char>(rng() & 0xff);
      break;
    case 1: {
      const std::size_t at = pick(text.size() + 1);
      text.erase(at, pick(std::min<std::size_t>(40, text.size() - at + 1)));
      break;
    }
    case 2:
      text.insert(pick(text.size() + 1), tokens[pick(tokens.size())]);
      break;
    case 3: {  // a number replaced by a token
      std::vector<std::size_t> digits;
      for (std::size_t i = 0; i < text.size(); ++i)
        if (std::isdigit(static_cast<unsigned char>(text[i])) && (i == 0 || !std::isdigit(static_cast<unsigned char>(text[i - 1]))))
          digits.push_back(i);
      if (digits.empty()) break;
      const std::size_t at = digits[pick(digits.size())];
      std::size_t end = at;
      while (end < text.size() && std::isdigit(static_cast<unsigned char>(text[end]))) ++end;
      text.replace(at, end - at, tokens[pick(tokens.size())]);
      break;
    }
    case 4:
      text.resize(pick(text.size() + 1));
      break;
    default: {  // a line repeated
      std::vector<std::size_t> starts = {0};
      for (std::size_t i = 0; i + 1 < text.size(); ++i)
        if (text[i] == '\n') starts.push_back(i + 1);
      const std::size_t k = pick(starts.size());
      const std::size_t end = k + 1 < starts.size() ? starts[k + 1] : text.size();
      text.insert(end, text.substr(starts[k], end - starts[k]));
    }
  }
  return text;
}

}  // namespace

// 600 mutants of a valid two-shard set: one to three edits of one shard's
// manifest or cells file; for half of the cells edits the manifest's digest
// is signed again, so that the edited cells reach the parser. Each set is
// either read or refused with std::invalid_argument and a one-line message
// (the sanitizer build runs this under ASan and UBSan): no other exception,
// crash or hang.
TEST(ShardFuzz, EveryMutatedShardSetIsReadOrRefusedInOneLine) {
  std::vector<std::string> originals;
  for (int k = 1; k <= 2; ++k) {
    LabOptions options;
    originals.push_back(scratch("fuzz-original" + std::to_string(k)));
    options.cells = std::make_shared<Cells>(ShardSpec{k, 2}, originals.back());
    sweep<double>(
        options, 7, [](std::size_t i) -> std::optional<double> { return 0.5 + static_cast<double>(i); },
        [](std::size_t, double&) {});
    options.cells->writeManifest("test", {"test", "--quick"});
  }
  ASSERT_NO_THROW(readShards(originals));
  std::mt19937 rng(20261203);
  int read = 0, refused = 0;
  for (int m = 0; m < 600; ++m) {
    std::vector<std::string> dirs;
    for (int k = 0; k < 2; ++k) {
      dirs.push_back(scratch("fuzz-mutant" + std::to_string(k)));
      std::filesystem::copy(originals[k], dirs.back());
    }
    const std::string& dir = dirs[rng() % 2];
    const bool cells = rng() % 2;
    const std::string path = dir + "/" + (cells ? kCellsFile : kManifestFile);
    std::string text = readText(path);
    for (int edits = 1 + static_cast<int>(rng() % 3); edits > 0; --edits) text = mutate(text, rng);
    writeText(path, text);
    if (cells && rng() % 2) {
      const std::string manifestPath = dir + "/" + kManifestFile;
      Json manifest = Json::parse(readText(manifestPath));
      manifest["cells_digest"] = hexDigest(fnv1a(text));
      writeText(manifestPath, manifest.dump(2) + "\n");
    }
    try {
      readShards(dirs);
      ++read;
    } catch (const std::invalid_argument& e) {
      ++refused;
      const std::string what = e.what();
      EXPECT_FALSE(what.empty()) << "mutant " << m;
      EXPECT_EQ(what.find('\n'), std::string::npos) << "mutant " << m << ": " << what;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "mutant " << m << " (" << path << "): " << typeid(e).name() << ": " << e.what();
    }
  }
  std::printf("[ fuzz     ] 600 mutants: %d read, %d refused\n", read, refused);
  EXPECT_GT(refused, 300);
  for (const auto& dir : originals) std::filesystem::remove_all(dir);
}
