#include "ui/palette.h"

#include <array>
#include <functional>

#include "core/face/face_landmarks.h"

namespace facehex::gui {

QColor constraintColour(const Constraint& constraint) {
  // Tableau 10 without its grey (reserved for context) and yellow (the selection preview), then black and white: ten,
  // so that the automatic set (six sides and four features) has no two alike. The first six go to the six shape ends
  // and must read well on the tissue colour; the features lie on the skin, tinted as side w1.
  static const std::array<QColor, 10> kColours = {
      QColor(31, 119, 180), QColor(255, 127, 14),  QColor(44, 160, 44), QColor(214, 39, 40), QColor(148, 103, 189),
      QColor(23, 190, 207), QColor(227, 119, 194), QColor(140, 86, 75), QColor(20, 20, 20),  QColor(255, 255, 255)};
  constexpr size_t kFeatureColours = kColours.size() - kNumSides;
  if (constraint.select.side) return kColours[static_cast<size_t>(*constraint.select.side)];
  const std::vector<FeatureSpec>& features = feature_specs();
  for (size_t i = 0; i < features.size(); ++i)
    if (features[i].name == constraint.name) return kColours[kNumSides + i % kFeatureColours];
  return kColours[std::hash<std::string>{}(constraint.name) % kColours.size()];
}

QColor fieldColour(int field) {
  static const std::array<QColor, 3> kColours = {QColor(220, 50, 47), QColor(40, 160, 60), QColor(38, 110, 220)};
  return kColours.at(field);
}

}  // namespace facehex::gui
