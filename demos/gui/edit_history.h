#pragma once
// Undo and redo for build mode: the documents a scene went through, each with
// the name of the edit that made it. An edit after an undo drops the redo
// states, as every editor does; the oldest states go beyond the capacity.
#include <cstddef>
#include <string>
#include <vector>

#include "scene_document.h"

namespace demo {

class EditHistory {
 public:
  explicit EditHistory(std::size_t capacity = 200);

  // The state every undo leads back to at most: forgets the rest.
  void reset(Json document, std::string what);
  // A new state after the current one (what: "add spring", "delete particles[2]").
  void push(Json document, std::string what);

  bool empty() const { return entries_.empty(); }
  const Json& current() const { return entries_.at(at_).document; }
  bool canUndo() const { return at_ > 0; }
  bool canRedo() const { return at_ + 1 < entries_.size(); }
  // Step back or forward; return the name of the edit undone or redone.
  // std::logic_error when there is none (check canUndo / canRedo).
  std::string undo();
  std::string redo();
  // What an undo or redo would do ("" when none).
  std::string nextUndo() const { return canUndo() ? entries_[at_].what : ""; }
  std::string nextRedo() const { return canRedo() ? entries_[at_ + 1].what : ""; }
  std::size_t position() const { return at_; }  // index of the current state
  std::size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    Json document;
    std::string what;  // the edit that led to this state
  };
  std::vector<Entry> entries_;
  std::size_t at_ = 0;
  std::size_t capacity_;
};

}  // namespace demo
