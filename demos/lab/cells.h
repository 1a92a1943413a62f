#pragma once
// The cells of an experiment's sweeps, and the shards that split them over
// processes and machines.
//
// An experiment enumerates its cells — the independent measurements of its
// sweeps — once, in one fixed order that no result changes: indices 0, 1, 2,
// ... as the experiment reaches them (`cell` takes one index, `sweep` a block).
// Every cell's result passes through JSON (lab/cell_json.h) on its way to the
// code that writes the rows, tables and values, so that code is the same in
// each of the three modes:
//   run     (no --shard): every cell is computed and the files are written;
//   shard   (--shard K/N): only the cells with index % N == K − 1 are
//           computed; their results go to DIR/cells.jsonl and, when the run
//           ends, the manifest DIR/shard.json; no CSV, table or value is written;
//   replay  (`particle-lab merge`): no cell is computed; every result is read
//           from the shards, and the experiment writes exactly the files an
//           unsharded run writes, tables and derived numbers from all cells.
//           A merge replays twice: first with its outputs held back, so that
//           every cell has been read back before anything is written (a cell
//           that does not read back leaves --out as it was), then writing.
#include <cstdint>
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "lab/cell_json.h"
#include "lab/lab.h"
#include "lab/parallel.h"
#include "output/output_file.h"

namespace lab {

// Shard K of N (1 ≤ K ≤ N) runs the cells whose index % N == K − 1.
struct ShardSpec {
  int index = 1;
  int count = 1;
};
// Reads "K/N"; throws std::invalid_argument naming the option and the value.
ShardSpec parseShard(const std::string& text);

// What a shard leaves in its output directory.
constexpr const char* kManifestFile = "shard.json";
constexpr const char* kCellsFile = "cells.jsonl";
// The manifest's "format_version": merge reads only this one.
// Version 2: the manifest records the digest of its cells file.
constexpr int kManifestFormatVersion = 2;

// FNV-1a (64 bits) of bytes, continued from `hash`: the digest a shard's
// manifest records of its cells file, so that a merge refuses cells changed
// after the shard wrote them. Written as 16 hex digits.
std::uint64_t fnv1a(const std::string& bytes, std::uint64_t hash = 0xcbf29ce484222325ull);
std::string hexDigest(std::uint64_t hash);

class Cells {
 public:
  enum class Mode { Run, Shard, Replay };
  // Every cell computed.
  Cells() = default;
  // Shard `spec` writing its cells into `dir` (removes an older manifest there).
  Cells(ShardSpec spec, const std::string& dir);
  // Every result recorded (cell index → result), none computed; shardNames[k]
  // names the shard holding the cells with index % N == k, for errors.
  // Without writeOutputs the replay only reads its cells back (writesOutputs() is false).
  explicit Cells(std::map<std::size_t, Json> recorded, std::vector<std::string> shardNames = {},
                 bool writeOutputs = true);

  Mode mode() const { return mode_; }
  // The shard this run computes (1/1 unless Mode::Shard).
  const ShardSpec& shard() const { return spec_; }
  // How many of the cells enumerated so far are this shard's (index % N == K − 1).
  long shardShare() const {
    const long k = spec_.index - 1, n = spec_.count, total = static_cast<long>(next_);
    return total > k ? (total - k + n - 1) / n : 0;
  }
  // How many cells this shard has computed and recorded.
  long recorded() const { return owned_; }
  // Whether the experiment writes its CSVs, tables and values (not in a
  // shard, nor in a merge's first replay).
  bool writesOutputs() const { return mode_ != Mode::Shard && writeOutputs_; }
  // Takes the next `count` indices; returns the first.
  std::size_t reserve(std::size_t count);
  // Cells enumerated so far.
  std::size_t count() const { return next_; }

  // The result of cell `index`: computed (a run, or the shard's own cell),
  // recorded (replay), or nullopt (another shard's cell, or compute gave
  // none: an interrupt). Safe from several threads.
  std::optional<Json> result(std::size_t index, const std::function<std::optional<Json>()>& compute);

  // Cell `index` was recorded in a form its result type does not read (a
  // missing key, a short array, a wrong type): throws std::invalid_argument
  // naming the shard in a replay, std::logic_error otherwise.
  [[noreturn]] void refuseRecorded(std::size_t index, const std::string& why) const;

  // A shard's manifest, written when its experiment finished: the format
  // version, the experiment, its arguments (without --shard, --out, --jobs), the shard, and the counts.
  void writeManifest(const std::string& experiment, const std::vector<std::string>& arguments);

 private:
  Mode mode_ = Mode::Run;
  bool writeOutputs_ = true;
  ShardSpec spec_;
  std::string dir_;
  std::size_t next_ = 0;
  long owned_ = 0;
  std::uint64_t cellsDigest_ = fnv1a("");  // of every byte written to the cells file
  std::map<std::size_t, Json> recorded_;
  std::vector<std::string> shardNames_;
  std::unique_ptr<output::OutputFile> cellsFile_;
  std::mutex mutex_;
};

// Cell `index`'s result as a Result, through its JSON (Cells::result).
template <class Result>
std::optional<Result> cellResult(Cells& cells, std::size_t index, const std::function<std::optional<Result>()>& compute) {
  const auto j = cells.result(index, [&]() -> std::optional<Json> {
    auto r = compute();
    if (!r) return std::nullopt;
    return encode(*r);
  });
  if (!j) return std::nullopt;
  Result r{};
  try {
    decode(*j, r);
  } catch (const CellShapeError& e) {
    cells.refuseRecorded(index, e.what());
  }
  return r;
}

// One cell: compute() (nullopt: interrupted) in a run or the owning shard,
// the recorded result in a replay, nullopt in another shard.
template <class Result>
std::optional<Result> cell(const LabOptions& options, const std::function<std::optional<Result>()>& compute) {
  return cellResult<Result>(*options.cells, options.cells->reserve(1), compute);
}

// `count` cells on options.jobs threads (parallelMap): deliver(k, result) in
// increasing k on this thread, for every cell that has a result here. `cost`,
// an estimate of each cell's run time, only orders their start.
template <class Result>
void sweep(const LabOptions& options, std::size_t count,
           const std::function<std::optional<Result>(std::size_t)>& compute,
           const std::function<void(std::size_t, Result&)>& deliver,
           const std::function<double(std::size_t)>& cost = {}) {
  const std::size_t base = options.cells->reserve(count);
  parallelMap<Result>(
      options.jobs, count,
      [&](std::size_t k) { return cellResult<Result>(*options.cells, base + k, [&] { return compute(k); }); },
      deliver, cost);
}

// `particle-lab merge`: reads the shards' manifests and cells and checks that
// they form one complete set (the manifest format this version reads, arguments
// that run the experiment named, the same experiment, arguments, shard count and
// cell count; every shard 1..N once; every cell present). Throws
// std::invalid_argument with one line naming what is wrong.
struct ShardSet {
  std::string experiment;
  std::vector<std::string> arguments;  // to run the experiment again, in replay
  std::map<std::size_t, Json> cells;
  std::size_t cellCount = 0;
  std::vector<std::string> shardNames;  // "shard K/N in 'DIR'", K = 1..N (Cells' shardNames)
};
ShardSet readShards(const std::vector<std::string>& dirs);

}  // namespace lab
