#pragma once
// The demo's colours, in one place: the renderer draws with them and the
// screenshot tests look for them.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace demo {

struct Rgb {
  std::uint8_t r, g, b;
};

namespace palette {
constexpr Rgb background{24, 27, 33};
constexpr Rgb paneBorder{70, 76, 90};
constexpr Rgb wall{84, 96, 122};          // a collider's body
constexpr Rgb wallOutline{176, 190, 216};  // and its outline, so that a thin one stands out
constexpr Rgb particle{236, 239, 244};
constexpr Rgb pinnedParticle{255, 96, 84};
constexpr Rgb grabbedParticle{120, 235, 140};
constexpr Rgb spring{86, 132, 190};
constexpr Rgb clothFront{62, 104, 160};  // a surface's faces (the cloth), at their rest area
constexpr Rgb clothBack{150, 84, 96};    // a face turned over (negative signed area): a fold
constexpr Rgb mouseSpring{120, 235, 140};
constexpr Rgb ghost{150, 220, 255};  // the closed-form motion beside the simulation
constexpr Rgb constraint{232, 178, 62};
constexpr Rgb constraintLoaded{255, 72, 48};  // the constraint carrying the pane's largest force
constexpr Rgb stretched{255, 156, 56};       // a spring or face at +strainFullScale
constexpr Rgb compressed{140, 232, 255};     // and at −strainFullScale
constexpr Rgb constraintForceArrow{255, 96, 226};  // Jᵀλ, which is no force object's
constexpr Rgb otherForceArrow{200, 200, 200};
constexpr Rgb divergenceText{255, 92, 150};
constexpr Rgb hudText{235, 235, 240};
constexpr Rgb buildSelection{90, 230, 255};  // build mode: the selected object's outline
constexpr Rgb buildGesture{255, 236, 140};   // build mode: the gesture being drawn, the particle it would snap to

// The stress colour map. A spring's strain (length over rest length, less 1)
// or a face's (area over rest area, less 1) moves its colour from the rest
// colour toward `stretched` or `compressed`, all the way at 10%.
constexpr double strainFullScale = 0.1;

inline Rgb mix(Rgb a, Rgb b, double t) {
  t = std::isfinite(t) ? std::clamp(t, 0.0, 1.0) : 1.0;
  auto channel = [t](std::uint8_t x, std::uint8_t y) {
    return static_cast<std::uint8_t>(std::lround(x + t * (static_cast<double>(y) - x)));
  };
  return {channel(a.r, b.r), channel(a.g, b.g), channel(a.b, b.b)};
}

inline Rgb strainColour(Rgb rest, double strain) {
  return strain >= 0.0 ? mix(rest, stretched, strain / strainFullScale) : mix(rest, compressed, -strain / strainFullScale);
}

// A constraint's colour from the force it applies over the largest in its
// pane (0…1): its kind's colour, turning red where it is loaded most.
inline Rgb constraintColour(Rgb kind, double relativeForce) { return mix(kind, constraintLoaded, relativeForce); }
}  // namespace palette

// The colours of each force and constraint type, by type(): the arrows of
// its load on the particles ("constraint": Jᵀλ, which is no object's) and
// the lines it sketches. A type not listed draws arrows in
// palette::otherForceArrow and lines in palette::spring. One row per type,
// as the scene file's codecs (scene_file/force_codecs.cpp) and the engine's
// fast paths (src/forces/force_kinds.cpp).
struct TypeColours {
  const char* type;
  Rgb arrow;
  Rgb line;
};
constexpr TypeColours typeColours[] = {
    // type            arrow                            line
    {"gravity", {90, 200, 255}, palette::spring},
    {"drag", {160, 160, 160}, palette::spring},
    {"spring", {255, 140, 60}, palette::spring},
    {"angular-spring", {200, 120, 255}, {196, 128, 255}},
    {"mouse-spring", {120, 235, 140}, palette::mouseSpring},
    {"wind", {120, 255, 230}, palette::spring},
    {"face-area", {255, 120, 150}, palette::spring},
    {"pressure", {255, 210, 90}, {255, 210, 90}},  // a gas ring's outline
    {"rod", palette::otherForceArrow, palette::constraint},
    {"circular-wire", palette::otherForceArrow, {176, 214, 92}},
    {"line", palette::otherForceArrow, {196, 200, 214}},
    {"constraint", palette::constraintForceArrow, palette::spring},
};

inline const TypeColours* typeColoursOf(const char* type) {
  for (const TypeColours& entry : typeColours)
    if (std::strcmp(entry.type, type) == 0) return &entry;
  return nullptr;
}

inline Rgb sketchColour(const char* type) {
  const TypeColours* entry = typeColoursOf(type);
  return entry ? entry->line : palette::spring;
}

inline Rgb forceArrowColour(const char* type) {
  const TypeColours* entry = typeColoursOf(type);
  return entry ? entry->arrow : palette::otherForceArrow;
}

}  // namespace demo
