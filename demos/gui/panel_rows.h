#pragma once
// Rows of the control panel that wrap: the next button or checkbox goes on
// the row of the last item when it fits in the panel's width, and starts a
// new row when it does not, so that a narrow window never cuts a label.
#include <imgui.h>

namespace demo {

// A button's width; a small button's too (it keeps the horizontal padding).
inline float buttonWidth(const char* label) {
  return ImGui::CalcTextSize(label, nullptr, true).x + 2.0f * ImGui::GetStyle().FramePadding.x;
}

inline float checkboxWidth(const char* label) {
  return ImGui::GetFrameHeight() + ImGui::GetStyle().ItemInnerSpacing.x + ImGui::CalcTextSize(label, nullptr, true).x;
}

// ImGui::SameLine() if an item `width` pixels wide fits after the last one.
inline void sameLineIfFits(float width) {
  const float right = ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + width;
  if (right <= ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x) ImGui::SameLine();
}

}  // namespace demo
