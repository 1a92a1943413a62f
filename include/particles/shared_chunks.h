#pragma once
// The end of a parallel pass shared out in chunks, so that threads whose
// fixed shares took different times still finish together.
//
// A pass has parts (one per thread), part p covering items
// [bounds[p], bounds[p + 1]). The first phase of the pass runs on fixed
// parts (each thread its own: work whose cost depends on the split, such as
// springs evaluated at both ends of a cut); when part p's first phase is
// done its owner opens it, and the second phase of part p, cut into chunks,
// may then run on any thread. drain() takes its own part's chunks first and
// then those of every other part as soon as that part is open, each chunk
// exactly once (an atomic counter per part). A second phase whose results do
// not depend on the thread that computes a chunk keeps the pass's bits the
// same on any split; only the time changes. Every part is opened by its
// owner, so a thread waiting for a part to open waits for a while, never
// for ever.
#include <atomic>
#include <memory>
#include <vector>

namespace particles {

class SharedChunks {
 public:
  // Parts from bounds (threads + 1 entries), every part closed.
  void reset(const std::vector<int>& bounds, int chunk) {
    const int parts = static_cast<int>(bounds.size()) - 1;
    if (parts != parts_) {
      queues_ = std::make_unique<Queue[]>(static_cast<std::size_t>(parts));
      parts_ = parts;
    }
    chunk_ = chunk;
    for (int p = 0; p < parts; ++p) {
      Queue& q = queues_[p];
      q.begin = bounds[p];
      q.end = bounds[p + 1];
      q.next.store(0, std::memory_order_relaxed);
      q.open.store(false, std::memory_order_relaxed);
    }
  }

  // Part p's first phase is done: its chunks may be taken (a release: the
  // writes made before it are seen by whoever takes a chunk).
  void open(int part) { queues_[part].open.store(true, std::memory_order_release); }

  // body(begin, end) on chunks until none is left: part `first`'s, then the
  // other parts' in turn, each once it is open. Returns the items done here.
  template <class Body>
  int drain(int first, const Body& body) {
    int done = 0;
    for (int k = 0; k < parts_; ++k) {
      Queue& q = queues_[(first + k) % parts_];
      while (!q.open.load(std::memory_order_acquire)) {
      }
      for (;;) {
        const int b = q.begin + chunk_ * q.next.fetch_add(1, std::memory_order_relaxed);
        if (b >= q.end) break;
        const int e = b + chunk_ < q.end ? b + chunk_ : q.end;
        body(b, e);
        done += e - b;
      }
    }
    return done;
  }

 private:
  struct alignas(64) Queue {  // one cache line per part: no false sharing between owners
    int begin = 0, end = 0;
    std::atomic<int> next{0};  // chunks taken so far
    std::atomic<bool> open{false};
  };
  std::unique_ptr<Queue[]> queues_;
  int parts_ = 0, chunk_ = 1;
};

}  // namespace particles
