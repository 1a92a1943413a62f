#include "lab/cells.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace lab {

Json encode(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return value;
}

void decode(const Json& j, double& value) {
  if (j.is_string()) {
    const std::string text = j.get<std::string>();
    if (text == "nan") value = std::nan("");
    else if (text == "inf") value = HUGE_VAL;
    else if (text == "-inf") value = -HUGE_VAL;
    else detail::wrongShape(j, "a number (or \"nan\", \"inf\", \"-inf\")");
    return;
  }
  if (!j.is_number()) detail::wrongShape(j, "a number");
  value = j.get<double>();
}

namespace detail {

void wrongShape(const Json& j, const std::string& what) {
  std::string text = j.dump();
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  throw CellShapeError("", "expected " + what + ", got " + text);
}

long long integerIn(const Json& j, long long lo, long long hi) {
  const std::string range = "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (j.is_number_unsigned()) {
    const auto value = j.get<std::uint64_t>();
    if (value > static_cast<std::uint64_t>(hi)) wrongShape(j, range);
    return static_cast<long long>(value);
  }
  if (!j.is_number_integer()) wrongShape(j, range);
  const auto value = j.get<std::int64_t>();
  if (value < lo || value > hi) wrongShape(j, range);
  return value;
}

}  // namespace detail

std::uint64_t fnv1a(const std::string& bytes, std::uint64_t hash) {
  for (const unsigned char c : bytes) {
    hash ^= c;
    hash *= 0x100000001b3ull;
  }
  return hash;
}

std::string hexDigest(std::uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

std::shared_ptr<Cells> allCells() { return std::make_shared<Cells>(); }

ShardSpec parseShard(const std::string& text) {
  const auto bad = [&] {
    return std::invalid_argument("--shard: expected K/N with 1 <= K <= N (shard K of N), got '" + text + "'");
  };
  const auto slash = text.find('/');
  if (slash == std::string::npos) throw bad();
  const auto number = [&](std::size_t from, std::size_t to) {
    int value = 0;
    const char* first = text.data() + from;
    const char* last = text.data() + to;
    if (first == last || *first == '0' || *first == '+') throw bad();
    const auto [end, error] = std::from_chars(first, last, value);
    if (error != std::errc() || end != last) throw bad();
    return value;
  };
  ShardSpec spec;
  spec.index = number(0, slash);
  spec.count = number(slash + 1, text.size());
  if (spec.index < 1 || spec.count < 1 || spec.index > spec.count) throw bad();
  return spec;
}

Cells::Cells(ShardSpec spec, const std::string& dir) : mode_(Mode::Shard), spec_(spec), dir_(dir) {
  createOutputDirectory(dir_);
  // An older manifest goes first: until this run ends the directory is no finished shard.
  const std::string manifest = dir_ + "/" + kManifestFile;
  std::error_code error;
  const auto status = std::filesystem::symlink_status(manifest, error);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw std::invalid_argument("cannot write the shard manifest file '" + manifest + "': not a regular file");
  std::filesystem::remove(manifest, error);
  if (error) throw std::invalid_argument("cannot remove the old shard manifest '" + manifest + "': " + error.message());
  cellsFile_ = std::make_unique<output::OutputFile>(dir_ + "/" + kCellsFile, "the shard's cells");
}

Cells::Cells(std::map<std::size_t, Json> recorded, std::vector<std::string> shardNames, bool writeOutputs)
    : mode_(Mode::Replay), writeOutputs_(writeOutputs), recorded_(std::move(recorded)), shardNames_(std::move(shardNames)) {}

void Cells::refuseRecorded(std::size_t index, const std::string& why) const {
  if (mode_ != Mode::Replay)
    throw std::logic_error("cell " + std::to_string(index) + " does not read back as its result: " + why);
  const std::string shard = shardNames_.empty() ? "a shard" : shardNames_[index % shardNames_.size()];
  throw std::invalid_argument("merge: " + shard + " holds a cell " + std::to_string(index) +
                              " that is not this experiment's (made by a different run or version): " + why);
}

std::size_t Cells::reserve(std::size_t count) {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::size_t first = next_;
  next_ += count;
  return first;
}

std::optional<Json> Cells::result(std::size_t index, const std::function<std::optional<Json>()>& compute) {
  if (mode_ == Mode::Replay) {
    const auto found = recorded_.find(index);
    if (found == recorded_.end())
      throw std::invalid_argument("merge: the shards hold no cell " + std::to_string(index) +
                                  " (made by a different version of the experiment?)");
    return found->second;
  }
  if (mode_ == Mode::Shard && static_cast<long>(index % spec_.count) != spec_.index - 1) return std::nullopt;
  const std::optional<Json> computed = compute();
  if (!computed) return std::nullopt;
  // The same text a shard records and a merge reads back, in every mode.
  const std::string text = computed->dump();
  if (mode_ == Mode::Shard) {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::string line = Json{{"cell", index}, {"result", Json::parse(text)}}.dump() + '\n';
    cellsFile_->stream() << line << std::flush;
    cellsDigest_ = fnv1a(line, cellsDigest_);
    cellsFile_->check();
    ++owned_;
  }
  return Json::parse(text);
}

void Cells::writeManifest(const std::string& experiment, const std::vector<std::string>& arguments) {
  if (mode_ != Mode::Shard) return;
  cellsFile_->close();
  const Json manifest = {{"format_version", kManifestFormatVersion},
                         {"experiment", experiment},
                         {"arguments", arguments},
                         {"shard", spec_.index},
                         {"shards", spec_.count},
                         {"cells", next_},
                         {"owned", owned_},
                         {"cells_digest", hexDigest(cellsDigest_)}};
  output::OutputFile out(dir_ + "/" + kManifestFile, "the shard manifest");
  out.stream() << manifest.dump(2) << '\n';
  out.close();
}

namespace {

// The text of "key"'s value as written in the JSON document `text` (the
// first such key; "" when it is not found): messages quote "1e3", not the
// 1000.0 the parser made of it.
std::string writtenValue(const std::string& text, const char* key) {
  const std::regex pattern("\"" + std::string(key) + "\"\\s*:\\s*([^,}\\]\\s]+)");
  std::smatch match;
  return std::regex_search(text, match, pattern) ? match[1].str() : std::string();
}

// object[key] as a count or index: a JSON integer >= 0 (get<std::size_t>
// would wrap a negative one round to 2^64 − 1). `text` is the document the
// object was read from, quoted in the message.
std::size_t countAt(const Json& object, const char* key, const std::string& text) {
  const Json& value = object.at(key);
  if (!value.is_number_unsigned()) {
    const std::string written = writtenValue(text, key);
    throw std::invalid_argument(std::string(key) + " must be an integer >= 0, got " +
                                (written.empty() ? value.dump() : written));
  }
  return value.get<std::size_t>();
}

// Deeper than any manifest or cell the laboratory writes (a few levels): a
// deeper document is refused while it is read, before copying or freeing it
// could recurse once per level.
constexpr int kMaxJsonDepth = 64;

struct TooDeep : std::invalid_argument {
  TooDeep() : std::invalid_argument("nested deeper than " + std::to_string(kMaxJsonDepth) + " levels") {}
};

template <class Input>
Json parseBounded(Input&& input) {
  return Json::parse(std::forward<Input>(input), [](int depth, Json::parse_event_t, Json&) {
    if (depth > kMaxJsonDepth) throw TooDeep();
    return true;
  });
}

// The document at path, parsed; its text into `text`.
Json readJson(const std::string& path, const std::string& what, std::string& text) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument("merge: no " + what + " '" + path + "' (not a shard, or its run did not finish)");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  text = bytes.str();
  try {
    return parseBounded(text);
  } catch (const Json::exception&) {
    throw std::invalid_argument("merge: malformed " + what + " '" + path + "'");
  } catch (const TooDeep& e) {
    throw std::invalid_argument("merge: malformed " + what + " '" + path + "': " + e.what());
  }
}

}  // namespace

namespace {

// One shard's manifest, as read and checked on its own.
struct Manifest {
  std::string path, experiment;
  std::vector<std::string> arguments;
  int index = 0, count = 0;
  std::size_t cells = 0;
  long owned = 0;
  std::string cellsDigest;
};

Manifest readManifest(const std::string& dir) {
  Manifest m;
  m.path = dir + "/" + kManifestFile;
  std::string text;
  const Json json = readJson(m.path, "shard manifest", text);
  const auto version = json.is_object() ? json.find("format_version") : json.end();
  if (version == json.end() || !version->is_number_integer() || *version != kManifestFormatVersion)
    throw std::invalid_argument("merge: shard manifest '" + m.path + "' has format version " +
                                (version == json.end() ? std::string("none") : version->dump()) +
                                ", this particle-lab reads version " + std::to_string(kManifestFormatVersion) +
                                " (made by a different version)");
  try {
    m.experiment = json.at("experiment").get<std::string>();
    m.arguments = json.at("arguments").get<std::vector<std::string>>();
    m.index = json.at("shard").get<int>();
    m.count = json.at("shards").get<int>();
    m.cells = countAt(json, "cells", text);
    m.owned = static_cast<long>(countAt(json, "owned", text));
    m.cellsDigest = json.at("cells_digest").get<std::string>();
  } catch (const Json::exception&) {
    throw std::invalid_argument("merge: malformed shard manifest '" + m.path + "'");
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("merge: malformed shard manifest '" + m.path + "': " + e.what());
  }
  if (m.arguments.empty() || m.arguments.front() != m.experiment)
    throw std::invalid_argument("merge: shard manifest '" + m.path + "' records arguments that do not run '" +
                                m.experiment + "'");
  return m;
}

// The manifest against the set's first one: same experiment, options, shard
// count and cell count; an index of its own.
void joinSet(const Manifest& m, const std::string& dir, const std::string& name, ShardSet& set,
             std::map<int, std::string>& seen, int& shards) {
  if (seen.empty()) {
    set.experiment = m.experiment, set.arguments = m.arguments, set.cellCount = m.cells, shards = m.count;
    set.shardNames.assign(m.count > 0 ? m.count : 0, std::string());
  } else if (m.experiment != set.experiment || m.arguments != set.arguments) {
    throw std::invalid_argument("merge: " + name + " ran a different experiment or options than '" +
                                seen.begin()->second + "'");
  } else if (m.count != shards || m.cells != set.cellCount) {
    throw std::invalid_argument("merge: " + name + " has " + std::to_string(m.cells) + " cells in " +
                                std::to_string(m.count) + " shards, '" + seen.begin()->second + "' " +
                                std::to_string(set.cellCount) + " in " + std::to_string(shards));
  }
  if (m.index < 1 || m.index > m.count)
    throw std::invalid_argument("merge: " + name + " is not a shard of " + std::to_string(m.count));
  if (!seen.emplace(m.index, dir).second)
    throw std::invalid_argument("merge: shard " + std::to_string(m.index) + "/" + std::to_string(m.count) +
                                " given twice ('" + seen[m.index] + "', '" + dir + "')");
  set.shardNames[m.index - 1] = name;
}

// The shard's cells file: its digest what the manifest recorded, every line
// one of this shard's cells, as many as it owned.
void readCells(const Manifest& m, const std::string& dir, const std::string& name, ShardSet& set) {
  const std::string path = dir + "/" + kCellsFile;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument("merge: " + name + " has no " + kCellsFile);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  const std::string text = bytes.str();
  if (hexDigest(fnv1a(text)) != m.cellsDigest)
    throw std::invalid_argument("merge: '" + path + "' is not the file its shard wrote (its digest " +
                                hexDigest(fnv1a(text)) + " differs from the manifest's " + m.cellsDigest + ")");
  std::istringstream lines(text);
  long read = 0;
  std::string line;
  while (std::getline(lines, line)) {
    std::size_t cell = 0;
    Json result;
    try {
      const Json row = parseBounded(line);
      cell = countAt(row, "cell", line);
      result = row.at("result");
    } catch (const Json::exception&) {
      throw std::invalid_argument("merge: malformed line " + std::to_string(read + 1) + " in '" + path + "'");
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("merge: malformed line " + std::to_string(read + 1) + " in '" + path + "': " +
                                  e.what());
    }
    if (cell >= m.cells || static_cast<int>(cell % m.count) != m.index - 1 || !set.cells.emplace(cell, result).second)
      throw std::invalid_argument("merge: " + name + " holds cell " + std::to_string(cell) +
                                  ", not one of its own (made by a different run or version)");
    ++read;
  }
  if (read != m.owned)
    throw std::invalid_argument("merge: " + name + " holds " + std::to_string(read) + " cells, its manifest says " +
                                std::to_string(m.owned));
}

}  // namespace

ShardSet readShards(const std::vector<std::string>& dirs) {
  if (dirs.empty()) throw std::invalid_argument("merge: no shard directories given");
  ShardSet set;
  std::map<int, std::string> seen;  // shard index → its directory
  int shards = 0;
  for (const std::string& dir : dirs) {
    const Manifest m = readManifest(dir);
    const std::string name = "shard " + std::to_string(m.index) + "/" + std::to_string(m.count) + " in '" + dir + "'";
    joinSet(m, dir, name, set, seen, shards);
    readCells(m, dir, name, set);
  }
  for (int k = 1; k <= shards; ++k)
    if (!seen.count(k))
      throw std::invalid_argument("merge: incomplete shard set: shard " + std::to_string(k) + "/" +
                                  std::to_string(shards) + " is missing");
  return set;
}

}  // namespace lab
