#include "edit_history.h"

#include <stdexcept>

namespace demo {

EditHistory::EditHistory(std::size_t capacity) : capacity_(capacity < 2 ? 2 : capacity) {}

void EditHistory::reset(Json document, std::string what) {
  entries_.clear();
  entries_.push_back({std::move(document), std::move(what)});
  at_ = 0;
}

void EditHistory::push(Json document, std::string what) {
  if (entries_.empty()) {
    reset(std::move(document), std::move(what));
    return;
  }
  entries_.resize(at_ + 1);
  entries_.push_back({std::move(document), std::move(what)});
  if (entries_.size() > capacity_) entries_.erase(entries_.begin());
  at_ = entries_.size() - 1;
}

std::string EditHistory::undo() {
  if (!canUndo()) throw std::logic_error("nothing to undo");
  return entries_[at_--].what;
}

std::string EditHistory::redo() {
  if (!canRedo()) throw std::logic_error("nothing to redo");
  return entries_[++at_].what;
}

}  // namespace demo
