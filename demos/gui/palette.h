#pragma once
// The demo's colours, in one place: the renderer draws with them and the
// screenshot tests look for them.
#include <cstdint>
#include <cstring>

namespace demo {

struct Rgb {
  std::uint8_t r, g, b;
};

namespace palette {
constexpr Rgb background{24, 27, 33};
constexpr Rgb paneBorder{70, 76, 90};
constexpr Rgb wall{58, 66, 82};
constexpr Rgb particle{236, 239, 244};
constexpr Rgb pinnedParticle{255, 96, 84};
constexpr Rgb grabbedParticle{120, 235, 140};
constexpr Rgb spring{86, 132, 190};
constexpr Rgb clothFront{62, 104, 160};  // a surface's faces (the cloth), at their rest area
constexpr Rgb clothBack{150, 84, 96};    // a face turned over (negative signed area): a fold
constexpr Rgb mouseSpring{120, 235, 140};
constexpr Rgb constraint{232, 178, 62};
constexpr Rgb constraintForceArrow{255, 214, 0};  // Jᵀλ, which is no force object's
constexpr Rgb otherForceArrow{200, 200, 200};
constexpr Rgb divergenceText{255, 92, 150};
constexpr Rgb hudText{235, 235, 240};
constexpr Rgb buildSelection{90, 230, 255};  // build mode: the selected object's outline
constexpr Rgb buildGesture{255, 236, 140};   // build mode: the gesture being drawn, the particle it would snap to
}  // namespace palette

// Arrow colour of each force type ("f"), by Force::type(); a type not listed
// draws in palette::otherForceArrow.
struct ForceColour {
  const char* type;
  Rgb colour;
};
constexpr ForceColour forceArrowColours[] = {
    {"gravity", {90, 200, 255}},
    {"spring", {255, 140, 60}},
    {"angular-spring", {200, 120, 255}},
    {"drag", {160, 160, 160}},
    {"mouse-spring", {120, 235, 140}},
    {"wind", {120, 255, 230}},
};

inline Rgb forceArrowColour(const char* type) {
  for (const ForceColour& entry : forceArrowColours)
    if (std::strcmp(entry.type, type) == 0) return entry.colour;
  return palette::otherForceArrow;
}

}  // namespace demo
